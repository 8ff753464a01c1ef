#pragma once
// The hexahedra's internal forces, four elements at a time.
//
// The explicit step spends most of its time in one formula applied to every
// element: deformation gradient, Kirchhoff stress, nodal forces, hourglass forces
// (elements.hpp, materials.hpp). Done one element at a time it is a chain of 3x3
// products that the compiler can only vectorise with shuffles. Here the same
// arithmetic runs on kHexLanes elements at once, one element per SIMD lane, on
// reference data stored lane by lane (structure of arrays), as in the vectorised
// element loops of production explicit codes. The elements of a batch share the
// material kind and whether they carry rebar, so no lane takes another branch.
//
// Two changes of arithmetic against elements.cpp, both exact in real numbers:
// - positions are taken relative to the element's node 0 (sum_i B_i = 0 and
//   sum_i h_ai = 0 make F and the hourglass modes independent of the origin),
//   which keeps the hourglass modes' cancellation at the element's size and not
//   at the tyre's radius;
// - the hourglass forces use gamma_ai = h_ai - hX_a . B_i with hX_a = sum_i h_ai X_i
//   (Flanagan & Belytschko 1981, eq. 24) without storing gamma:
//   q_a = sum_j h_aj x_j - F hX_a, f_i += k (sum_a h_ai q_a - Q B_i), Q = sum_a q_a (x) hX_a.
// J^(-1/3) of the rubber comes from Newton's iteration for the inverse cube root
// instead of cbrt, with cbrt kept for a lane that Newton has not brought to a
// residual of 1e-14. Results agree with elements.cpp to rounding
// (tests/tyre_fe/test_tyre_hex8_batch.cpp).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "tyre_fe/elements.hpp"
#include "tyre_fe/materials.hpp"

namespace tyre_fe {

struct Model3d;

inline constexpr int kHexLanes = 4;
using HexLanes = double __attribute__((vector_size(kHexLanes * sizeof(double))));

struct Hex8Batch {
  enum class Kind { yeoh, elastic };
  HexLanes gradient_per_m[8][3];      // B_i = volume-mean dN_i/dX
  HexLanes hourglass_base_m[4][3];    // hX_a = sum_i h_ai (X_i - X_0)
  HexLanes volume_m3;
  HexLanes hourglass_stiffness_N_per_m;  // c G V sum_i |B_i|^2
  HexLanes bulk_viscosity_Pa_s;       // b1 rho c L_e: the viscous pressure is this times tr(D)
  // Yeoh: C10, C20, C30, K0. St. Venant-Kirchhoff: lambda, mu (the rest zero).
  HexLanes material_Pa[4];
  HexLanes rebar_direction[3];        // reference unit direction a0
  HexLanes rebar_modulus_Pa;          // phi E
  int node[8][kHexLanes];
  int element[kHexLanes];             // the hexahedron of each lane; -1: padding
  Kind kind = Kind::yeoh;
  bool has_rebar = false;
};

// Where each hexahedron's forces land in the batched force array: node a of
// hexahedron e has its x, y, z forces at offset(e, a) + 0, + kHexLanes, + 2 kHexLanes.
struct Hex8Batches {
  std::vector<Hex8Batch> batches;
  std::vector<int> batch_of, lane_of;  // per hexahedron
  std::size_t force_offset(std::size_t element, int node) const {
    return (static_cast<std::size_t>(batch_of[element]) * 24 + node * 3) * kHexLanes + lane_of[element];
  }
  std::size_t force_array_size() const { return batches.size() * 24 * kHexLanes; }
};

// What one lane needs: the element's reference data and nodes, its material and rebar,
// and the coefficient of its bulk viscosity.
struct Hex8LaneInput {
  const Hex8Reference* reference = nullptr;
  const double (*reference_position_m)[3] = nullptr;  // X of the 8 nodes
  std::array<int, 8> nodes{};
  const SolidMaterial* material = nullptr;
  double hourglass_coefficient = 0.0;
  double bulk_viscosity_Pa_s = 0.0;  // b1 rho c L_e
  Eigen::Vector3d rebar_direction = Eigen::Vector3d::Zero();
  double rebar_modulus_Pa = 0.0;     // phi E
  int element = -1;                  // -1: padding
};

// Fills lane `lane` of a batch (whose kind must be the material's).
void set_hex8_lane(Hex8Batch& batch, int lane, const Hex8LaneInput& input);

// Groups the model's hexahedra by (material kind, rebar) in their mesh order and
// fills the lanes; the last batch of a group repeats its first element as padding.
Hex8Batches build_hex8_batches(const Model3d& model);

// Per-element results of one batch, written for the real lanes only.
struct Hex8ElementResults {
  double* energy_J;            // strain + hourglass energy
  double* hourglass_energy_J;
  double* viscous_power_W;     // bulk viscosity, <= 0 (work done on the body)
};

// Asks for a batch's reference data ahead of its use: the batches stream from memory
// once per step (about 1.6 kB each), and the hardware prefetcher does not run ahead
// across them on its own.
inline void prefetch_hex8_batch(const Hex8Batch& batch) {
  const char* p = reinterpret_cast<const char*>(&batch);
  for (std::size_t offset = 0; offset < sizeof(Hex8Batch); offset += 64) __builtin_prefetch(p + offset);
}

// Internal forces (the gradient of the element energy, entering the equation of
// motion with a minus sign) of one batch into force[24 * kHexLanes] (node, axis,
// lane), with the linear bulk viscosity when with_bulk_viscosity.
void hex8_batch_forces(const Hex8Batch& batch, const double* const position[3],
                       const double* const velocity[3], bool with_bulk_viscosity, double* force,
                       const Hex8ElementResults& results);

}  // namespace tyre_fe
