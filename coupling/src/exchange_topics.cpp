#include "cosim_coupling/exchange_topics.hpp"

namespace cosim::coupling {
namespace {

// The exchange types and their topics have the same fields, expanded from one
// table (cosim/wire_fields.hpp); the topics add a header, the mesh topic the
// tyre's node ids. One copy of the table's fields serves both directions.
#define COSIM_COPY_FIELD(type, name, init) b.name = a.name;

template <class From, class To>
void copy_kinematics(const From& a, To& b) {
  COSIM_WIRE_FIELDS_SurfaceKinematics(COSIM_COPY_FIELD)
}

template <class From, class To>
void copy_loads(const From& a, To& b) {
  COSIM_WIRE_FIELDS_ContactLoads(COSIM_COPY_FIELD)
}

template <class From, class To>
void copy_topology(const From& a, To& b) {
  COSIM_WIRE_FIELDS_SurfaceTopology(COSIM_COPY_FIELD)
}

#undef COSIM_COPY_FIELD

}  // namespace

void to_topic(const SurfaceState& s, std::uint64_t run_id, transport::SurfaceKinematics& k) {
  k.header = {run_id, s.exchange, s.time_s};
  copy_kinematics(s, k);
}

void from_topic(const transport::SurfaceKinematics& k, SurfaceState& s) {
  s.exchange = k.header.step, s.time_s = k.header.sim_time_s;
  copy_kinematics(k, s);
}

void to_topic(const SurfaceLoads& l, std::uint64_t run_id, transport::ContactLoads& out) {
  out.header = {run_id, l.exchange, l.time_s};
  copy_loads(l, out);
}

void from_topic(const transport::ContactLoads& l, SurfaceLoads& out) {
  out.exchange = l.header.step, out.time_s = l.header.sim_time_s;
  copy_loads(l, out);
}

void to_topic(const SurfaceTopology& t, transport::SurfaceMesh& out) { copy_topology(t, out); }

void from_topic(const transport::SurfaceMesh& m, SurfaceTopology& out) { copy_topology(m, out); }

}  // namespace cosim::coupling
