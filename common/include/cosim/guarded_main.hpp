#pragma once
// A program's main() body under the one error protocol of every program
// (tyre_fe, snow_sph, coupler, cosim): a cosim::Error (bad input: a scene, an
// option, a sample) prints "PROGRAM: error: ..." and exits 2; any other
// exception is the program's own fault, "PROGRAM: internal error: ...", exit 3.
// Otherwise the exit code is `body`'s.
#include <cstdio>
#include <exception>
#include <functional>

#include "cosim/error.hpp"

namespace cosim {

inline int guarded_main(const char* program, const std::function<int()>& body) {
  try {
    return body();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", program, e.what());
    return 3;
  }
}

}  // namespace cosim
