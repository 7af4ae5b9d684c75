#pragma once
// The message of the ccdlab::Error a callable throws, or "no error": lets tests assert whole messages.
#include <functional>
#include <string>

#include "framework/util/error.hpp"

namespace ccdlab::test {

inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace ccdlab::test
