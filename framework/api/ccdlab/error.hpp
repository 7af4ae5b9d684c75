#pragma once
// The one exception type of ccdlab: every user-facing failure (a bad file, bad YAML, a bad argument or option).
// Messages are located: "file:line: field: expected …, got …", or name the call ("ccdlab::Detector::step: …").
// Installed with the C++ API (ccdlab/ccdlab.hpp); the framework throws the same type (framework/util/error.hpp).
#include <stdexcept>

namespace ccdlab {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ccdlab
