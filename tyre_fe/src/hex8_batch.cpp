// Batched hexahedron forces (see hex8_batch.hpp). The formulas are those of
// elements.cpp (one-point hex, Flanagan-Belytschko hourglass) and materials.cpp
// (Yeoh, St. Venant-Kirchhoff, smeared rebar), written once for a vector of lanes.
#include "tyre_fe/hex8_batch.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include "tyre_fe/model3d.hpp"

namespace tyre_fe {
namespace {

using V = HexLanes;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

V splat(double value) { return V{} + value; }

V lanewise_log(V v) {
  V out;
  for (int l = 0; l < kHexLanes; ++l) out[l] = std::log(v[l]);
  return out;
}

// J^(-1/3) by Newton's iteration y <- y (4 - J y^3) / 3 from the second-order Taylor
// guess at J = 1, whose relative error e_n = J y_n^3 - 1 falls as e_{n+1} ~ -(2/3) e_n^2:
// four steps reach the rounding level for 0.8 < J < 1.25 (|e_0| < 5e-3), which
// covers the rubber (K0 / mu0 = 100 or more). Lanes outside are finished by cbrt.
V inverse_cube_root(V J) {
  const V d = J - 1.0;
  V y = 1.0 - d * (1.0 / 3.0) + d * d * (2.0 / 9.0);
  for (int iteration = 0; iteration < 4; ++iteration) y = y * (4.0 - J * y * y * y) * (1.0 / 3.0);
  const V residual = J * y * y * y - 1.0;
  for (int l = 0; l < kHexLanes; ++l)
    if (!(std::fabs(residual[l]) <= 1e-14)) y[l] = J[l] > 0.0 ? 1.0 / std::cbrt(J[l]) : kNaN;
  return y;
}

// NaN in every lane whose deformation gradient is inverted (det F <= 0), 0 elsewhere,
// so that the step's finiteness check on the residual catches it outside the loop.
V inverted_marker(V J) { return J > 0.0 ? splat(0.0) : splat(kNaN); }

// tau = 2 dU/dI1b dev(Bbar) + K0 J (J - 1) I (materials.cpp, yeoh_kirchhoff).
V yeoh_stress(const Hex8Batch& b, const V F[3][3], V J, V tau[3][3]) {
  const V C10 = b.material_Pa[0], C20 = b.material_Pa[1], C30 = b.material_Pa[2], K = b.material_Pa[3];
  V B[3][3];
  for (int k = 0; k < 3; ++k)
    for (int l = k; l < 3; ++l) B[k][l] = F[k][0] * F[l][0] + F[k][1] * F[l][1] + F[k][2] * F[l][2];
  const V y = inverse_cube_root(J);
  const V J_m23 = y * y;
  const V trace_B = B[0][0] + B[1][1] + B[2][2];
  const V x = J_m23 * trace_B - 3.0;
  const V dU_dI1b = C10 + x * (2.0 * C20 + 3.0 * C30 * x);
  const V deviatoric = 2.0 * dU_dI1b * J_m23;
  const V diagonal = K * J * (J - 1.0) - deviatoric * trace_B * (1.0 / 3.0) + inverted_marker(J);
  for (int k = 0; k < 3; ++k)
    for (int l = k; l < 3; ++l) tau[k][l] = tau[l][k] = deviatoric * B[k][l];
  for (int k = 0; k < 3; ++k) tau[k][k] += diagonal;
  return x * (C10 + x * (C20 + x * C30)) + 0.5 * K * (J - 1.0) * (J - 1.0) + inverted_marker(J);
}

// tau = F S F^T, S = lambda tr(E) I + 2 mu E (materials.cpp, svk_kirchhoff).
V elastic_stress(const Hex8Batch& b, const V F[3][3], V J, V tau[3][3]) {
  const V lambda = b.material_Pa[0], mu = b.material_Pa[1];
  V E[3][3];
  for (int k = 0; k < 3; ++k)
    for (int l = k; l < 3; ++l)
      E[k][l] = E[l][k] = 0.5 * (F[0][k] * F[0][l] + F[1][k] * F[1][l] + F[2][k] * F[2][l]) - (k == l ? 0.5 : 0.0);
  const V trace_E = E[0][0] + E[1][1] + E[2][2];
  V S[3][3];
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) S[k][l] = 2.0 * mu * E[k][l] + (k == l ? lambda * trace_E : splat(0.0));
  V FS[3][3];
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) FS[k][l] = F[k][0] * S[0][l] + F[k][1] * S[1][l] + F[k][2] * S[2][l];
  for (int k = 0; k < 3; ++k)
    for (int l = k; l < 3; ++l)
      tau[k][l] = tau[l][k] = FS[k][0] * F[l][0] + FS[k][1] * F[l][1] + FS[k][2] * F[l][2] + inverted_marker(J);
  V EE = splat(0.0);
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) EE += E[k][l] * E[k][l];
  return 0.5 * lambda * trace_E * trace_E + mu * EE + inverted_marker(J);
}

// tau += phi E ln(lambda) a (x) a, W = phi E (ln lambda)^2 / 2 (materials.cpp).
V add_rebar_stress(const Hex8Batch& b, const V F[3][3], V tau[3][3]) {
  V stretched[3];
  for (int k = 0; k < 3; ++k)
    stretched[k] = F[k][0] * b.rebar_direction[0] + F[k][1] * b.rebar_direction[1] + F[k][2] * b.rebar_direction[2];
  const V stretch_sq = stretched[0] * stretched[0] + stretched[1] * stretched[1] + stretched[2] * stretched[2];
  const V log_stretch = 0.5 * lanewise_log(stretch_sq);
  const V axial = b.rebar_modulus_Pa * log_stretch;
  const V scale = axial / stretch_sq;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) tau[k][l] += scale * stretched[k] * stretched[l];
  return 0.5 * axial * log_stretch;
}

// The stages of batch_forces below. Each is inlined into every instantiation of
// it (always_inline), so the kernel compiles to the instructions it did as one
// function: the same speed, and the same results to the bit.

// The element's node positions relative to its node 0, gathered lane by lane.
[[gnu::always_inline]] inline void gather_positions(const Hex8Batch& b, const double* const position[3], V x[8][3]) {
  for (int k = 0; k < 3; ++k) {
    V origin;
    for (int l = 0; l < kHexLanes; ++l) origin[l] = position[k][b.node[0][l]];
    for (int a = 0; a < 8; ++a) {
      V p;
      for (int l = 0; l < kHexLanes; ++l) p[l] = position[k][b.node[a][l]];
      x[a][k] = p - origin;
    }
  }
}

// F = sum_a x_a (x) B_a at the centre and its cofactor C; returns J = det F.
[[gnu::always_inline]] inline V deformation_gradient(const Hex8Batch& b, const V x[8][3], V F[3][3], V C[3][3]) {
  const auto& B = b.gradient_per_m;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      V sum = x[0][k] * B[0][l];
      for (int a = 1; a < 8; ++a) sum += x[a][k] * B[a][l];
      F[k][l] = sum;
    }
  // cof(F) = det(F) F^-T, by columns: [f1 x f2, f2 x f0, f0 x f1].
  for (int j = 0; j < 3; ++j) {
    const int p = (j + 1) % 3, q = (j + 2) % 3;
    C[0][j] = F[1][p] * F[2][q] - F[2][p] * F[1][q];
    C[1][j] = F[2][p] * F[0][q] - F[0][p] * F[2][q];
    C[2][j] = F[0][p] * F[1][q] - F[1][p] * F[0][q];
  }
  return F[0][0] * C[0][0] + F[1][0] * C[1][0] + F[2][0] * C[2][0];
}

// Linear bulk viscosity added to tau: tr(D) = tr(dv/dX F^-1) = (dv/dX : cof F) / J;
// sigma_v = b1 rho c L_e tr(D) I. Returns its power (negative: dissipated).
[[gnu::always_inline]] inline V add_bulk_viscosity(const Hex8Batch& b, const double* const velocity[3], const V C[3][3], V J, V tau[3][3]) {
  const auto& B = b.gradient_per_m;
  V dvdX_cof = splat(0.0);
  for (int k = 0; k < 3; ++k) {
    // Gathered into plain arrays and copied whole: writing a vector's lanes
    // one by one reads it first, which GCC 12 takes for a use uninitialised.
    V v[8];
    for (int a = 0; a < 8; ++a) {
      double lanes[kHexLanes];
      for (int l = 0; l < kHexLanes; ++l) lanes[l] = velocity[k][b.node[a][l]];
      std::memcpy(&v[a], lanes, sizeof lanes);
    }
    for (int l = 0; l < 3; ++l) {
      V dv = v[0] * B[0][l];
      for (int a = 1; a < 8; ++a) dv += v[a] * B[a][l];
      dvdX_cof += dv * C[k][l];
    }
  }
  const V trace_D = dvdX_cof / J;
  const V Jq = J * b.bulk_viscosity_Pa_s * trace_D;
  for (int k = 0; k < 3; ++k) tau[k][k] += Jq;
  return -b.volume_m3 * Jq * trace_D;
}

// The nodal forces, written to `force`: the stress's, V0 P B_a, and the
// hourglass control's. Returns the hourglass energy.
[[gnu::always_inline]] inline V nodal_forces(const Hex8Batch& b, const V x[8][3], const V F[3][3], const V C[3][3], V J, const V tau[3][3],
               double* force) {
  const auto& B = b.gradient_per_m;
  // V0 P = (V0 / J) tau cof(F).
  const V scale = b.volume_m3 / J;
  V M[3][3];
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) M[k][l] = scale * (tau[k][0] * C[0][l] + tau[k][1] * C[1][l] + tau[k][2] * C[2][l]);

  // Hourglass modes q_a = sum_j h_aj x_j - F hX_a, energy k/2 sum_a |q_a|^2.
  const V k_hg = b.hourglass_stiffness_N_per_m;
  V q[4][3];
  V hourglass_sq = splat(0.0);
  for (int m = 0; m < 4; ++m)
    for (int k = 0; k < 3; ++k) {
      V sum = kHex8HourglassPattern[m][1] * x[1][k];  // x[0] = 0
      for (int j = 2; j < 8; ++j) sum += kHex8HourglassPattern[m][j] * x[j][k];
      for (int l = 0; l < 3; ++l) sum -= F[k][l] * b.hourglass_base_m[m][l];
      hourglass_sq += sum * sum;
      q[m][k] = k_hg * sum;
    }
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l)
      for (int m = 0; m < 4; ++m) M[k][l] -= q[m][k] * b.hourglass_base_m[m][l];

  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) {
      V f = M[k][0] * B[i][0] + M[k][1] * B[i][1] + M[k][2] * B[i][2];
      for (int m = 0; m < 4; ++m) f += kHex8HourglassPattern[m][i] * q[m][k];
      std::memcpy(force + (i * 3 + k) * kHexLanes, &f, sizeof f);
    }
  return 0.5 * k_hg * hourglass_sq;
}

template <Hex8Batch::Kind kKind, bool kRebar>
void batch_forces(const Hex8Batch& b, const double* const position[3], const double* const velocity[3],
                  bool with_bulk_viscosity, double* force, const Hex8ElementResults& results) {
  V x[8][3];  // relative to node 0
  gather_positions(b, position, x);
  V F[3][3], C[3][3];
  const V J = deformation_gradient(b, x, F, C);

  V tau[3][3];
  V energy_density;
  if constexpr (kKind == Hex8Batch::Kind::yeoh)
    energy_density = yeoh_stress(b, F, J, tau);
  else
    energy_density = elastic_stress(b, F, J, tau);
  if constexpr (kRebar) energy_density += add_rebar_stress(b, F, tau);

  V viscous_power = splat(0.0);
  if (with_bulk_viscosity) viscous_power = add_bulk_viscosity(b, velocity, C, J, tau);

  const V hourglass_energy = nodal_forces(b, x, F, C, J, tau, force);
  const V energy = energy_density * b.volume_m3 + hourglass_energy;
  for (int l = 0; l < kHexLanes; ++l) {
    const int e = b.element[l];
    if (e < 0) continue;
    results.energy_J[e] = energy[l];
    results.hourglass_energy_J[e] = hourglass_energy[l];
    results.viscous_power_W[e] = viscous_power[l];
  }
}

}  // namespace

void hex8_batch_forces(const Hex8Batch& batch, const double* const position[3],
                       const double* const velocity[3], bool with_bulk_viscosity, double* force,
                       const Hex8ElementResults& results) {
  using Kind = Hex8Batch::Kind;
  if (batch.kind == Kind::yeoh)
    batch.has_rebar ? batch_forces<Kind::yeoh, true>(batch, position, velocity, with_bulk_viscosity, force, results)
                    : batch_forces<Kind::yeoh, false>(batch, position, velocity, with_bulk_viscosity, force, results);
  else
    batch.has_rebar ? batch_forces<Kind::elastic, true>(batch, position, velocity, with_bulk_viscosity, force, results)
                    : batch_forces<Kind::elastic, false>(batch, position, velocity, with_bulk_viscosity, force, results);
}

void set_hex8_lane(Hex8Batch& b, int l, const Hex8LaneInput& in) {
  const Hex8Reference& ref = *in.reference;
  const SolidMaterial& solid = *in.material;
  const auto* X = in.reference_position_m;
  for (int a = 0; a < 8; ++a) {
    b.node[a][l] = in.nodes[a];
    for (int k = 0; k < 3; ++k) b.gradient_per_m[a][k][l] = ref.dNdX[a][k];
  }
  for (int h = 0; h < 4; ++h)
    for (int k = 0; k < 3; ++k) {
      double sum = 0.0;
      for (int a = 1; a < 8; ++a) sum += kHex8HourglassPattern[h][a] * (X[a][k] - X[0][k]);
      b.hourglass_base_m[h][k][l] = sum;
    }
  b.volume_m3[l] = ref.volume_m3;
  b.hourglass_stiffness_N_per_m[l] =
      in.hourglass_coefficient * solid.shear_modulus_Pa() * ref.volume_m3 * ref.gradient_sq_sum_per_m2;
  b.bulk_viscosity_Pa_s[l] = in.bulk_viscosity_Pa_s;
  if (solid.kind == SolidMaterial::Kind::yeoh) {
    b.material_Pa[0][l] = solid.yeoh.C10_Pa, b.material_Pa[1][l] = solid.yeoh.C20_Pa;
    b.material_Pa[2][l] = solid.yeoh.C30_Pa, b.material_Pa[3][l] = solid.yeoh.bulk_modulus_Pa;
  } else {
    const double E = solid.elastic.youngs_modulus_Pa, nu = solid.elastic.poisson_ratio;
    b.material_Pa[0][l] = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    b.material_Pa[1][l] = E / (2.0 * (1.0 + nu));
    b.material_Pa[2][l] = b.material_Pa[3][l] = 0.0;
  }
  for (int k = 0; k < 3; ++k) b.rebar_direction[k][l] = in.rebar_direction[k];
  b.rebar_modulus_Pa[l] = in.rebar_modulus_Pa;
  b.element[l] = in.element;
}

Hex8Batches build_hex8_batches(const Model3d& m) {
  const std::size_t ne = m.mesh.hexes.size();
  Hex8Batches out;
  out.batch_of.assign(ne, -1);
  out.lane_of.assign(ne, -1);
  const double b1 = m.options.bulk_viscosity_linear;
  for (Hex8Batch::Kind kind : {Hex8Batch::Kind::yeoh, Hex8Batch::Kind::elastic})
    for (bool rebar : {false, true}) {
      std::vector<std::size_t> group;
      for (std::size_t e = 0; e < ne; ++e) {
        const bool yeoh = m.materials.solid[m.material[e]].kind == SolidMaterial::Kind::yeoh;
        if ((kind == Hex8Batch::Kind::yeoh) == yeoh && (m.rebar_fraction[e] > 0.0) == rebar) group.push_back(e);
      }
      for (std::size_t start = 0; start < group.size(); start += kHexLanes) {
        Hex8Batch b{};
        b.kind = kind;
        b.has_rebar = rebar;
        for (int l = 0; l < kHexLanes; ++l) {
          const bool real = start + l < group.size();
          const std::size_t e = real ? group[start + l] : group[start];  // padding repeats the first
          double X[8][3];
          Hex8LaneInput in;
          for (int a = 0; a < 8; ++a) {
            in.nodes[a] = m.mesh.hexes[e][a];
            for (int k = 0; k < 3; ++k) X[a][k] = m.mesh.nodes[in.nodes[a]][k];
          }
          in.reference = &m.reference[e];
          in.reference_position_m = X;
          in.material = &m.materials.solid[m.material[e]];
          in.hourglass_coefficient = m.materials.hourglass_coefficient;
          in.bulk_viscosity_Pa_s = b1 * m.element_density[e] * m.element_wave_speed[e] * m.reference[e].characteristic_length_m;
          in.rebar_direction = m.rebar_direction[e];
          in.rebar_modulus_Pa = m.rebar_fraction[e] * m.rebar_modulus_Pa[e];
          in.element = real ? static_cast<int>(e) : -1;
          set_hex8_lane(b, l, in);
          if (real) out.batch_of[e] = static_cast<int>(out.batches.size()), out.lane_of[e] = l;
        }
        out.batches.push_back(b);
      }
    }
  return out;
}

}  // namespace tyre_fe
