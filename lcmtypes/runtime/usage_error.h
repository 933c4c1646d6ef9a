// Bad flags or input files given to a program: its main prints the message
// and exits with status 2 (other failures exit with 1).
#pragma once

#include <stdexcept>

namespace mrsim {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mrsim
