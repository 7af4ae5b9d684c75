#pragma once
// One exception type for every user-facing failure (bad file, bad YAML, bad argument). Messages are located:
// "file:line: field: expected …, got …". Thrown once at the boundary; algorithms assume valid input.
#include <stdexcept>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "framework/api/ccdlab/error.hpp"  // class Error (the C++ API installs it)

namespace ccdlab {


/// `text` cut to `max` characters with every byte outside printable ASCII written as \xNN: file content
/// quoted in an error message (a corrupt or binary file) stays one readable line.
inline std::string printable(std::string_view text, std::size_t max = 32) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < max; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) out += char(c);
    else out += fmt::format("\\x{:02x}", c);
  }
  if (text.size() > max) out += "...";
  return out;
}

/// Throws Error with a fmt-formatted message.
template <class... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace ccdlab
