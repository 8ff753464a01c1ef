// libFuzzer target: what the three programs do with a sample of the run's
// per-step topics before they trust it (docs/reliability.md, "Bad input,
// fuzzed"), on samples built from any bytes: wrong sequence lengths, node and
// facet numbers out of range, NaN and infinities, facet tags outside the
// enumeration, another run's id, a step from the past or the future, long
// sequences. The path is the handlers' own: the sample filter (run id, step),
// the copy from the wire type (cosim_coupling/exchange_topics.hpp) and the
// checks every receiver runs (cosim/surface_exchange.hpp, coupler/wire.hpp);
// then, for samples that pass, what the coupler computes from them (friction
// per facet, facet geometry, the loads per facet, the force decomposition).
// A bad sample must be dropped by the filter or refused with cosim::Error; no
// input may crash, read or write out of bounds, or hit undefined behaviour.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "coupler/facet_geometry.hpp"
#include "coupler/forces.hpp"
#include "coupler/friction.hpp"
#include "coupler/wire.hpp"
#include "cosim/error.hpp"
#include "cosim/surface_exchange.hpp"
#include "cosim_coupling/exchange_topics.hpp"
#include "cosim_transport/sample_filter.hpp"

namespace {

namespace tp = cosim::transport;
constexpr std::uint64_t kRun = 0x5eed;

// A length up to twice `typical`, sometimes anything up to the bytes left (a long sequence).
std::size_t length(FuzzedDataProvider& in, std::size_t typical) {
  if (in.ConsumeIntegralInRange<int>(0, 7) == 0)
    return in.ConsumeIntegralInRange<std::size_t>(0, in.remaining_bytes() / 4 + 1);
  return in.ConsumeIntegralInRange<std::size_t>(0, 2 * typical);
}
// One in eight sequences is wild (raw bits: NaN, infinities, denormals;
// indices of any size), so that most samples get past the first check and
// reach the ones behind it.
bool wild(FuzzedDataProvider& in) { return in.ConsumeIntegralInRange<int>(0, 7) == 0; }
double value(FuzzedDataProvider& in, bool raw = false) {
  return raw && in.ConsumeBool() ? in.ConsumeFloatingPoint<double>() : in.ConsumeFloatingPointInRange<double>(-2.0, 2.0);
}
std::vector<double> values(FuzzedDataProvider& in, std::size_t n) {
  const bool raw = wild(in);
  std::vector<double> v(n);
  for (auto& x : v) x = value(in, raw);
  return v;
}
// Indices in [0, range), or in a wild sequence sometimes anything.
std::vector<std::uint32_t> indices(FuzzedDataProvider& in, std::size_t n, std::uint32_t range) {
  const bool raw = wild(in) || range == 0;
  std::vector<std::uint32_t> v(n);
  for (auto& i : v)
    i = raw && in.ConsumeBool() ? in.ConsumeIntegral<std::uint32_t>() : in.ConsumeIntegralInRange<std::uint32_t>(0, range - 1);
  return v;
}
tp::SampleHeader header(FuzzedDataProvider& in, std::uint64_t step) {
  tp::SampleHeader h;
  h.run_id = in.ConsumeBool() ? kRun : in.ConsumeIntegral<std::uint64_t>();
  h.step = in.ConsumeBool() ? step : in.ConsumeIntegral<std::uint64_t>();
  h.sim_time_s = value(in, true);
  return h;
}

std::size_t g_decomposed = 0;  // samples that reached the decomposition (printed at exit)
struct Report {
  ~Report() { std::fprintf(stderr, "fuzz_samples: %zu inputs reached the force decomposition\n", g_decomposed); }
} g_report;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const std::uint64_t step = in.ConsumeIntegral<std::uint64_t>();
  tp::SampleFilter filter(kRun);
  filter.expect_step(step);

  // The surface mesh (the coupler and the terrain check it once).
  tp::SurfaceMesh mesh;
  mesh.header = header(in, 0);
  const std::size_t nodes = length(in, 12), facets = length(in, 6);
  mesh.node_ids = indices(in, nodes, 1000);
  mesh.x_m = values(in, in.ConsumeBool() ? nodes : length(in, 12));
  mesh.y_m = values(in, nodes), mesh.z_m = values(in, nodes);
  mesh.facet_nodes = indices(in, in.ConsumeBool() ? 4 * facets : length(in, 24), static_cast<std::uint32_t>(nodes));
  mesh.facet_tags.resize(in.ConsumeBool() ? facets : length(in, 6));
  const bool wild_tags = wild(in);
  for (auto& t : mesh.facet_tags)
    t = static_cast<cosim::FacetTag>(wild_tags ? in.ConsumeIntegral<std::uint8_t>()
                                               : in.ConsumeIntegralInRange<int>(0, cosim::kFacetTagCount - 1));
  mesh.node_mass_kg = values(in, in.ConsumeBool() ? nodes : 0);
  cosim::SurfaceTopology topology;
  try {
    cosim::coupling::from_topic(mesh, topology);
    cosim::check_surface_topology(topology, "SurfaceMesh");
  } catch (const cosim::Error&) {
    return 0;
  }
  const auto facet_count = static_cast<std::uint32_t>(topology.facet_tags.size());
  const auto node_count = static_cast<std::uint32_t>(topology.x_m.size());

  // The kinematics of one step, as the coupler (friction not yet set) or the terrain (friction required) gets it.
  tp::SurfaceKinematics k;
  k.header = header(in, step);
  const std::size_t near = length(in, node_count);
  k.nodes = indices(in, near, node_count);
  k.x_m = values(in, near), k.y_m = values(in, in.ConsumeBool() ? near : length(in, near));
  k.z_m = values(in, near), k.vx_mps = values(in, near), k.vy_mps = values(in, near), k.vz_mps = values(in, near);
  k.facets = indices(in, length(in, facet_count), facet_count);
  const bool at_terrain = in.ConsumeBool();
  k.friction_coefficient = values(in, at_terrain ? k.facets.size() : 0);
  if (!filter.accept(k.header)) return 0;  // another run's or another step's: dropped and counted
  cosim::SurfaceState state;
  try {
    cosim::coupling::from_topic(k, state);
    cosim::check_surface_state(state, topology, "SurfaceKinematics", at_terrain);
  } catch (const cosim::Error&) {
    return 0;
  }
  // The coupler's friction per listed facet.
  coupler::FrictionRules rules;
  std::vector<double> mu;
  try {
    coupler::fill_facet_friction(topology.facet_tags, state.facets, in.ConsumeBool(), coupler::TerrainKind::snow_soft,
                                 rules, mu);
  } catch (const cosim::Error&) {
    return 0;
  }

  // The wheel and the terrain's loads of the same step.
  tp::WheelState wheel;
  wheel.header = header(in, step);
  const bool raw = wild(in);
  wheel.rim_x_m = value(in, raw), wheel.rim_z_m = value(in, raw), wheel.reaction_moment_y_Nm = value(in, raw);
  wheel.spin_rate_radps = value(in, raw), wheel.rim_longitudinal_force_N = value(in, raw);
  tp::ContactLoads loads;
  loads.header = header(in, step);
  const std::size_t loaded = length(in, node_count);
  loads.nodes = indices(in, loaded, node_count);
  loads.fx_N = values(in, loaded), loads.fy_N = values(in, loaded), loads.fz_N = values(in, loaded);
  const std::size_t touched = length(in, facet_count);
  loads.facets = indices(in, touched, facet_count);
  for (auto* v : {&loads.normal_force_N, &loads.pressure_x_N, &loads.pressure_y_N, &loads.pressure_z_N,
                  &loads.tangential_x_N, &loads.tangential_y_N, &loads.tangential_z_N, &loads.contact_area_m2,
                  &loads.pressure_Pa})
    *v = values(in, in.ConsumeIntegralInRange<int>(0, 15) == 0 ? length(in, touched) : touched);
  try {
    coupler::check_wheel_state(wheel, "WheelState");
    cosim::SurfaceLoads checked;
    cosim::coupling::from_topic(loads, checked);
    cosim::check_surface_loads(checked, topology, "ContactLoads");
  } catch (const cosim::Error&) {
    return 0;
  }
  // What the coupler makes of them.
  std::vector<double> x = topology.x_m, y = topology.y_m, z = topology.z_m;
  for (std::size_t j = 0; j < state.nodes.size(); ++j)
    x[state.nodes[j]] = state.x_m[j], y[state.nodes[j]] = state.y_m[j], z[state.nodes[j]] = state.z_m[j];
  try {
    const coupler::FacetGeometry geometry = coupler::quad_facet_geometry(x, y, z, topology.facet_nodes);
    const coupler::FacetLoads facet_loads = coupler::facet_loads_from_contact(loads, topology.facet_tags, geometry);
    const coupler::ForceDecomposition d = coupler::decompose_forces(facet_loads, coupler::wheel_input(wheel, 0.36));
    (void)coupler::decomposition_residual_N(facet_loads, 0.0, 0.0, 0.0);
    (void)coupler::force_summary(d, loads.header);
    ++g_decomposed;
  } catch (const cosim::Error&) {
  }
  return 0;
}
