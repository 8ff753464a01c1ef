#pragma once
// SPH smoothing kernels in 3D, as functions of q = r / h.
//  - cubic B-spline: Monaghan & Lattanzio (1985), support 2h (default);
//  - quadratic: Johnson, Stryk & Beissel (1996), Comput. Methods Appl. Mech.
//    Eng. 139, eq. for W = C (3/16 q^2 - 3/4 q + 3/4), support 2h;
//  - quintic spline: Morris, Fox & Zhu (1997), J. Comput. Phys. 136, support 3h.
// Normalisation constants are the 3D ones (Liu & Liu 2003, ch. 3).
#include <algorithm>
#include <cmath>

namespace snow_sph {

enum class KernelType { cubic, quadratic, quintic };

struct Kernel {
  KernelType type = KernelType::cubic;
  double h = 0.0;            // smoothing length [m]
  double support = 0.0;      // support radius [m]
  double norm = 0.0;         // normalisation constant / h^3 folded in
  double inv_h = 0.0;

  static Kernel make(KernelType type, double h) {
    constexpr double pi = 3.14159265358979323846;
    Kernel k;
    k.type = type;
    k.h = h;
    k.inv_h = 1.0 / h;
    const double h3 = h * h * h;
    switch (type) {
      case KernelType::cubic: k.support = 2.0 * h; k.norm = 1.0 / (pi * h3); break;
      case KernelType::quadratic: k.support = 2.0 * h; k.norm = 5.0 / (4.0 * pi * h3); break;
      case KernelType::quintic: k.support = 3.0 * h; k.norm = 1.0 / (120.0 * pi * h3); break;
    }
    return k;
  }

  // W(r).
  double value(double r) const {
    switch (type) {
      case KernelType::cubic: return value_t<KernelType::cubic>(r);
      case KernelType::quadratic: return value_t<KernelType::quadratic>(r);
      case KernelType::quintic: return value_t<KernelType::quintic>(r);
    }
    return 0.0;
  }
  double gradient_over_r(double r) const {
    switch (type) {
      case KernelType::cubic: return gradient_over_r_t<KernelType::cubic>(r);
      case KernelType::quadratic: return gradient_over_r_t<KernelType::quadratic>(r);
      case KernelType::quintic: return gradient_over_r_t<KernelType::quintic>(r);
    }
    return 0.0;
  }

  // Compile-time kernel choice for the hot loops.
  template <KernelType T>
  double value_t(double r) const {
    const double q = r * inv_h;
    switch (T) {
      case KernelType::cubic:
        if (q < 1.0) return norm * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
        if (q < 2.0) { const double a = 2.0 - q; return norm * 0.25 * a * a * a; }
        return 0.0;
      case KernelType::quadratic:
        if (q < 2.0) return norm * (0.1875 * q * q - 0.75 * q + 0.75);
        return 0.0;
      case KernelType::quintic: {
        if (q >= 3.0) return 0.0;
        const double a = 3.0 - q, b = 2.0 - q, c = 1.0 - q;
        double w = a * a * a * a * a;
        if (q < 2.0) w -= 6.0 * b * b * b * b * b;
        if (q < 1.0) w += 15.0 * c * c * c * c * c;
        return norm * w;
      }
    }
    return 0.0;
  }

  // (1/r) dW/dr, so that grad_i W_ij = (x_i - x_j) * this; zero beyond the
  // support. Branch-free (the hot loops evaluate it for every listed pair).
  template <KernelType T>
  double gradient_over_r_t(double r) const {
    return gradient_over_r_t<T>(r, 1.0 / r);
  }
  template <KernelType T>
  double gradient_over_r_t(double r, double inv_r) const {
    const double q = r * inv_h;
    const double c = norm * inv_h;  // dW/dr = norm * dw/dq / h
    if constexpr (T == KernelType::cubic) {
      const double a = q < 2.0 ? 2.0 - q : 0.0;  // ternaries, not std::max: they vectorise
      const double inner = c * inv_h * (-3.0 + 2.25 * q);  // (-3q + 2.25q^2) / q / h
      const double outer = -0.75 * c * a * a * inv_r;
      return q < 1.0 ? inner : outer;
    } else if constexpr (T == KernelType::quadratic) {
      const double a = q < 2.0 ? 1.0 : 0.0;
      return a * c * (0.375 * q - 0.75) * inv_r;
    } else {
      const double a = q < 3.0 ? 3.0 - q : 0.0, b = q < 2.0 ? 2.0 - q : 0.0, e = q < 1.0 ? 1.0 - q : 0.0;
      const double a2 = a * a, b2 = b * b, e2 = e * e;
      return c * (-5.0 * a2 * a2 + 30.0 * b2 * b2 - 75.0 * e2 * e2) * inv_r;
    }
  }
};

}  // namespace snow_sph
