#pragma once
// The 3D tyre's state in a checkpoint (cosim/checkpoint.hpp, docs/reliability.md):
// node positions and half-step velocities, the forces of the last step and
// their parts (their work is booked with the next half step), the element
// forces and energies, the rim, the road's stick anchors, the energies, the
// clock. The model (mesh, masses, materials) is rebuilt from the scene.
#include "cosim/checkpoint.hpp"
#include "tyre_fe/solver3d.hpp"

namespace tyre_fe {

void save_state(const State3d& s, cosim::CheckpointWriter& out);
// Into a state made from the same scene (same nodes, elements and rim nodes).
void restore_state(const cosim::CheckpointReader& in, State3d& s);

}  // namespace tyre_fe
