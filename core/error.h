#pragma once
// InvalidInput: the user asked for something the renderer refuses (a degenerate camera,
// a zero-sized image). The message names the setting and the problem, in one line.

#include <stdexcept>

namespace rtiow {

class InvalidInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rtiow
