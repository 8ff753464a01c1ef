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

// The coupling with a terrain, between two windows (docs/reliability.md,
// "Coupled runs"): the surface's positions and node masses when the tyre joined
// (the topology is rebuilt from the mesh), the exchanges done, the sub-steps,
// the band, the last loads' totals and the impulses; and the agreed window.
void save_terrain_coupling(const TerrainCoupling& t, double window_s, cosim::CheckpointWriter& out);
// Into t.surface made from the same mesh; returns the saved window [s].
double restore_terrain_coupling(const cosim::CheckpointReader& in, TerrainCoupling& t);

}  // namespace tyre_fe
