#pragma once
// One exception type for every user-facing failure (bad file, bad YAML, bad argument). Messages are located:
// "file:line: field: expected …, got …". Thrown once at the boundary; algorithms assume valid input.
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace ccdlab {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws Error with a fmt-formatted message.
template <class... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace ccdlab
