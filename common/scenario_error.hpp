// The error every problem of a scenario's configuration is reported with.
#pragma once

#include <stdexcept>

namespace wsn::common {

/// A scenario that could not be loaded: what() reads "file:line: what was expected".
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace wsn::common
