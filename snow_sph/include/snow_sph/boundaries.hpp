#pragma once
// Rigid free-slip walls and symmetry planes by mirror (ghost) particles
// (Libersky et al. 1993, J. Comput. Phys. 109): each particle closer to a
// plane than the neighbour-list radius gets a mirror image whose velocity
// normal to the plane and shear stresses on the plane are reversed. For a
// planar free-slip wall the mirror image is exact, so walls and symmetry
// planes are the same operation. Ghost pressure carries the hydrostatic
// increment rho g . (x_ghost - x), so a fluid at rest is in equilibrium at the
// floor. A no-slip wall's images reverse the whole velocity and keep the
// shear stresses (Morris, Fox & Zhu 1997, J. Comput. Phys. 136); a Coulomb
// wall is a free-slip one plus the friction of ground_friction.hpp.
#include <vector>

#include "snow_sph/model.hpp"

namespace snow_sph {

// Drops old ghosts and creates new ones for particles within `range` of a
// plane (corners and edges get images over two or three planes).
void make_ghosts(Model& model, double range);

// Copies the current state of each ghost's source, mirrored.
void refresh_ghost_kinematics(Model& model);  // positions, velocities
void refresh_ghost_state(Model& model);       // density, stress, pressure

// Signs of the shear components of a tensor mirrored over the planes in `mask`.
struct ShearFlips {
  double xy = 1, yz = 1, xz = 1;
};
ShearFlips ghost_shear_flips(const Model& model, std::uint8_t mask);

// A particle closer to a rigid wall than half a spacing is pushed back with
// an acceleration c^2/(dx/2) (1 - d/(dx/2))^2: at the wall its own mirror
// image coincides with it and exerts no force (the kernel gradient vanishes
// at r = 0), so without this a particle that reaches a wall sticks to it.
// Adds to (ax, ay, az); power[i] receives the wall's power on particle i.
// Particles at rest outside the active domain (Particles::active) are left alone.
void wall_repulsion(const Model& model, double* ax, double* ay, double* az, double* power);

// Last resort: a real particle found beyond a wall is reflected back inside
// and its normal velocity removed. Returns how many were.
std::size_t clamp_to_walls(Model& model);

}  // namespace snow_sph
