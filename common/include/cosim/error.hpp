#pragma once
// The project's one exception type. Library code throws it; only a program's
// main() turns it into an exit code and a message.
#include <cstdio>
#include <stdexcept>
#include <string>

namespace cosim {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// A number for a message, with its precision (std::to_string prints 2.6e-6 as
// 0.000003): six significant digits, exponent form where it is shorter.
inline std::string number_text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

// Source revision recorded at build time (git describe).
const char* source_revision();

}  // namespace cosim
