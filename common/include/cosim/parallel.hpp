#pragma once
// One labelled helper for every parallel loop (OpenMP). Loops written through
// it gather only (each iteration writes its own index), so results are the
// same on any thread count.
#include <cstddef>
#include <omp.h>

namespace cosim {

template <class Body>
inline void parallel_for(const char* /*label*/, std::size_t n, Body&& body) {
  const long count = static_cast<long>(n);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < count; ++i) body(static_cast<std::size_t>(i));
}

inline int max_threads() { return omp_get_max_threads(); }

}  // namespace cosim
