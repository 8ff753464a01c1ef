// The probe's lock-step exchange: see probe.hpp.
#include "probe.hpp"

#include <algorithm>
#include <cmath>

#include "cosim/error.hpp"
#include "cosim_transport/handshake.hpp"
#include "cosim_transport/sample_filter.hpp"

namespace cosim::transport::probe {

namespace {

using Clock = std::chrono::steady_clock;

// Value of field `f` of entry `i` at `step`: distinct per field, entry and step.
double value(int f, std::uint64_t step, std::size_t i) {
  return f * 1000.0 + static_cast<double>(step) * 1e-3 + static_cast<double>(i) * 1e-7;
}
void fill(std::vector<double>& v, std::size_t n, int f, std::uint64_t step) {
  v.resize(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = value(f, step, i);
}
void indices(std::vector<std::uint32_t>& v, std::size_t n, std::uint32_t stride, std::uint64_t step) {
  v.resize(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::uint32_t>(i * stride + step % stride);
}
SampleHeader header(std::uint64_t run_id, std::uint64_t step) { return {run_id, step, static_cast<double>(step) * 1e-5}; }

template <class V>
void expect(const V& got, const V& want, const char* topic, const char* field) {
  if (got == want) return;
  std::size_t i = 0;
  while (i < std::min(got.size(), want.size()) && got[i] == want[i]) ++i;
  throw Error(std::string(topic) + "." + field + " differs from what was sent (sizes " + std::to_string(got.size()) +
              " and " + std::to_string(want.size()) + ", first difference at " + std::to_string(i) + ")");
}
void expect(double got, double want, const char* topic, const char* field) {
  if (!(got == want)) throw Error(std::string(topic) + "." + field + " differs from what was sent");
}
void expect_header(const SampleHeader& got, const SampleHeader& want, const char* topic) {
  if (got.run_id != want.run_id || got.step != want.step || got.sim_time_s != want.sim_time_s)
    throw Error(std::string(topic) + ".header differs from what was sent (step " + std::to_string(got.step) +
                ", expected " + std::to_string(want.step) + ")");
}

template <class T>
std::size_t payload_bytes(const std::vector<T>& v) { return v.size() * sizeof(T); }

struct Endpoints {
  std::unique_ptr<Participant> participant;
  std::unique_ptr<Writer<RunControl>> control_out;
  std::unique_ptr<Reader<RunControl>> control_in;
};

Endpoints open(const ProbeOptions& o) {
  if (o.nodes < 4) throw Error("probe: --nodes must be >= 4 (got " + std::to_string(o.nodes) + ")");
  if (o.steps < 1 || o.warmup_steps < 0) throw Error("probe: --steps must be >= 1 and --warmup >= 0");
  Endpoints e;
  e.participant = make_participant(o.vendor, o.transport);
  e.control_out = e.participant->create_writer<RunControl>();
  e.control_in = e.participant->create_reader<RunControl>();
  return e;
}

}  // namespace

SurfaceMesh make_mesh(std::uint64_t run_id, int nodes) {
  SurfaceMesh m;
  const auto n = static_cast<std::size_t>(nodes);
  m.header = header(run_id, 0);
  indices(m.node_ids, n, 3, 0);
  fill(m.x_m, n, 1, 0);
  fill(m.y_m, n, 2, 0);
  fill(m.z_m, n, 3, 0);
  indices(m.facet_nodes, 4 * n, 1, 0);
  m.facet_tags.resize(n);
  for (std::size_t i = 0; i < n; ++i) m.facet_tags[i] = static_cast<FacetTag>(i % kFacetTagCount);
  return m;
}

SurfaceKinematics make_kinematics(std::uint64_t run_id, std::uint64_t step, int nodes) {
  SurfaceKinematics k;
  const auto n = static_cast<std::size_t>(nodes);
  k.header = header(run_id, step);
  indices(k.nodes, n, 2, step);
  fill(k.x_m, n, 1, step);
  fill(k.y_m, n, 2, step);
  fill(k.z_m, n, 3, step);
  fill(k.vx_mps, n, 4, step);
  fill(k.vy_mps, n, 5, step);
  fill(k.vz_mps, n, 6, step);
  indices(k.facets, n, 2, step);
  fill(k.friction_coefficient, n, 7, step);
  return k;
}

ContactLoads make_loads(std::uint64_t run_id, std::uint64_t step, int nodes) {
  ContactLoads l;
  const auto n = static_cast<std::size_t>(nodes / 4);
  l.header = header(run_id, step);
  indices(l.nodes, n, 4, step);
  fill(l.fx_N, n, 11, step);
  fill(l.fy_N, n, 12, step);
  fill(l.fz_N, n, 13, step);
  indices(l.facets, n, 4, step);
  fill(l.normal_force_N, n, 14, step);
  fill(l.pressure_x_N, n, 20, step);
  fill(l.pressure_y_N, n, 21, step);
  fill(l.pressure_z_N, n, 22, step);
  fill(l.tangential_x_N, n, 15, step);
  fill(l.tangential_y_N, n, 16, step);
  fill(l.tangential_z_N, n, 17, step);
  fill(l.contact_area_m2, n, 18, step);
  fill(l.pressure_Pa, n, 19, step);
  l.particle_reach_z_m = value(23, step, 0);
  return l;
}

// Every field of the topic (cosim/wire_fields.hpp) against what was sent.
#define COSIM_PROBE_EXPECT_FIELD(type, name, init) expect(got.name, w.name, topic, #name);
#define COSIM_PROBE_EXPECT_SAMPLE(T)                         \
  void expect_sent(const T& got, const T& w) {               \
    const char* topic = #T;                                  \
    expect_header(got.header, w.header, topic);              \
    COSIM_WIRE_FIELDS_##T(COSIM_PROBE_EXPECT_FIELD)          \
  }
COSIM_PROBE_EXPECT_SAMPLE(SurfaceMesh)
COSIM_PROBE_EXPECT_SAMPLE(SurfaceKinematics)
COSIM_PROBE_EXPECT_SAMPLE(ContactLoads)
#undef COSIM_PROBE_EXPECT_SAMPLE
#undef COSIM_PROBE_EXPECT_FIELD

void check_mesh(const SurfaceMesh& got, std::uint64_t run_id, int nodes) {
  expect_sent(got, make_mesh(run_id, nodes));
}
void check_kinematics(const SurfaceKinematics& got, std::uint64_t run_id, std::uint64_t step, int nodes) {
  expect_sent(got, make_kinematics(run_id, step, nodes));
}
void check_loads(const ContactLoads& got, std::uint64_t run_id, std::uint64_t step, int nodes) {
  expect_sent(got, make_loads(run_id, step, nodes));
}

ProbeResult run_ping(const ProbeOptions& o) {
  Endpoints e = open(o);
  auto mesh_out = e.participant->create_writer<SurfaceMesh>();
  auto kin_out = e.participant->create_writer<SurfaceKinematics>();
  auto loads_in = e.participant->create_reader<ContactLoads>();
  mesh_out->write(make_mesh(o.run_id, o.nodes));
  HandshakeOptions h{o.run_id, Role::tyre, {Role::terrain}, 0.0, o.timeout};
  h.data_endpoints = {kin_out.get(), loads_in.get()};
  handshake(*e.control_out, *e.control_in, h);

  ProbeResult r;
  SampleFilter filter(o.run_id);
  SurfaceKinematics k = make_kinematics(o.run_id, 0, o.nodes);
  ContactLoads loads;
  r.kinematics_bytes = payload_bytes(k.nodes) + 6 * payload_bytes(k.x_m) + payload_bytes(k.facets) +
                       payload_bytes(k.friction_coefficient);
  const int total = o.warmup_steps + o.steps;
  for (int s = 0; s < total; ++s) {
    const auto step = static_cast<std::uint64_t>(s);
    k = make_kinematics(o.run_id, step, o.nodes);  // outside the timed part, like the solver's own work
    filter.expect_step(step);
    const auto t0 = Clock::now();
    kin_out->write(k);
    if (!wait_for_accepted(*loads_in, filter, loads, o.timeout))
      throw Error("ping: no ContactLoads for step " + std::to_string(step) + " within " +
                  std::to_string(o.timeout.count()) + " ms");
    const auto t1 = Clock::now();
    if (o.check_content) check_loads(loads, o.run_id, step, o.nodes);
    if (s >= o.warmup_steps) {
      r.step_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
      ++r.steps;
    }
  }
  r.loads_bytes = payload_bytes(loads.nodes) + 3 * payload_bytes(loads.fx_N) + payload_bytes(loads.facets) +
                  9 * payload_bytes(loads.normal_force_N);
  RunControl stop;
  stop.header = {o.run_id, static_cast<std::uint64_t>(total), 0.0};
  stop.kind = ControlKind::stop;
  stop.sender = Role::tyre;
  stop.reason = "probe finished";
  e.control_out->write(stop);
  e.control_out->wait_for_acknowledgments(std::chrono::milliseconds(2000));
  r.rejected = filter.rejected();
  return r;
}

ProbeResult run_pong(const ProbeOptions& o) {
  Endpoints e = open(o);
  auto mesh_in = e.participant->create_reader<SurfaceMesh>();
  auto kin_in = e.participant->create_reader<SurfaceKinematics>();
  auto loads_out = e.participant->create_writer<ContactLoads>();
  HandshakeOptions h{o.run_id, Role::terrain, {Role::tyre}, 0.0, o.timeout};
  h.data_endpoints = {mesh_in.get(), kin_in.get(), loads_out.get()};
  const HandshakeResult hs = handshake(*e.control_out, *e.control_in, h);

  ProbeResult r;
  SampleFilter filter(o.run_id);
  SurfaceMesh mesh;
  if (!wait_for_accepted(*mesh_in, filter, mesh, o.timeout)) throw Error("pong: the durable SurfaceMesh never arrived");
  if (o.check_content) check_mesh(mesh, o.run_id, o.nodes);

  SurfaceKinematics k;
  const int total = o.warmup_steps + o.steps;
  for (int s = 0; s < total; ++s) {
    const auto step = static_cast<std::uint64_t>(s);
    filter.expect_step(step);
    if (!wait_for_accepted(*kin_in, filter, k, o.timeout))
      throw Error("pong: no SurfaceKinematics for step " + std::to_string(step) + " within " +
                  std::to_string(o.timeout.count()) + " ms");
    if (o.check_content) check_kinematics(k, o.run_id, step, o.nodes);
    loads_out->write(make_loads(o.run_id, step, o.nodes));
    ++r.steps;
  }
  // Wait for STOP (it may already have come during the handshake's tail).
  bool stopped = false;
  for (const auto& m : hs.other_messages) stopped = stopped || m.kind == ControlKind::stop;
  SampleFilter control_filter(o.run_id);
  RunControl m;
  while (!stopped) {
    if (!wait_for_accepted(*e.control_in, control_filter, m, o.timeout)) throw Error("pong: no STOP from ping");
    stopped = m.kind == ControlKind::stop && m.sender == Role::tyre;
  }
  r.rejected = filter.rejected();
  return r;
}

double percentile(std::vector<double> v, double fraction) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
}

}  // namespace cosim::transport::probe
