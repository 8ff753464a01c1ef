#include "snow_sph/particles.hpp"

namespace snow_sph {

void Particles::permute_real(const std::vector<std::uint32_t>& order) {
  const std::size_t n = order.size();
  std::vector<double> tmp(n);
  for (auto* f : real_fields()) {
    for (std::size_t k = 0; k < n; ++k) tmp[k] = (*f)[order[k]];
    std::copy(tmp.begin(), tmp.end(), f->begin());
  }
  auto permute = [&](auto& v) {
    auto copy = v;
    for (std::size_t k = 0; k < n; ++k) v[k] = copy[order[k]];
  };
  permute(material);
  permute(id);
  permute(neighbour_count);
  permute(active);
  permute(moving);
}

}  // namespace snow_sph
