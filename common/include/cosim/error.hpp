#pragma once
// The project's one exception type. Library code throws it; only a program's
// main() turns it into an exit code and a message.
#include <stdexcept>
#include <string>

namespace cosim {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Source revision recorded at build time (git describe).
const char* source_revision();

}  // namespace cosim
