#include "snow_sph/particles.hpp"

#include <cmath>

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

// 3/2 s:s = ((sxx - syy)^2 + (syy - szz)^2 + (szz - sxx)^2) / 2 + 3 (sxy^2 + syz^2 + sxz^2).
double von_mises_stress_Pa(const Particles& p, std::size_t i) {
  const double a = p.sxx[i] - p.syy[i], b = p.syy[i] - p.szz[i], c = p.szz[i] - p.sxx[i];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (p.sxy[i] * p.sxy[i] + p.syz[i] * p.syz[i] + p.sxz[i] * p.sxz[i]));
}

}  // namespace snow_sph
