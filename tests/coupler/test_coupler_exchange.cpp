// What the coupler keeps of each exchange (coupler/exchange_forces.hpp,
// coupler/exchange_payload.hpp): the surface's node positions as the exchanges
// list them, the row of forces.csv, and the payload counters, through a
// checkpoint. Exact comparisons: values are copied, and the payload's means are
// quotients of small integers by a power of two.
#include <gtest/gtest.h>

#include <string>

#include "cosim/checkpoint.hpp"
#include "coupler/exchange_forces.hpp"
#include "coupler/exchange_payload.hpp"
#include "test_paths.hpp"

namespace tp = cosim::transport;

TEST(CouplerExchange, ListedNodesMoveTheOthersStay) {
  coupler::SurfacePositions s;
  s.x_m = {0, 1, 2}, s.y_m = {0, 0, 0}, s.z_m = {5, 5, 5};
  tp::SurfaceKinematics k;
  k.nodes = {2, 0};
  k.x_m = {2.5, 0.5}, k.y_m = {1, 2}, k.z_m = {4, 3};
  s.update(k);
  EXPECT_EQ(s.x_m, (std::vector<double>{0.5, 1, 2.5}));
  EXPECT_EQ(s.y_m, (std::vector<double>{2, 0, 1}));
  EXPECT_EQ(s.z_m, (std::vector<double>{3, 5, 4}));
}

TEST(CouplerExchange, ForcesCsvRowHasOneValuePerNamedColumn) {
  coupler::ExchangeForces f;
  f.d.traction_force_N = 3, f.d.drawbar_pull_N = -2, f.d.vertical_pressure_force_groove_N = 9;
  f.total_x_N = 7, f.total_z_N = 11;
  tp::WheelState wheel;
  wheel.rim_longitudinal_force_N = 13, wheel.reaction_moment_y_Nm = 17;
  const auto& columns = coupler::forces_csv_columns();
  const std::vector<double> row = coupler::forces_csv_row(0.25, 40, f, wheel);
  ASSERT_EQ(row.size(), columns.size());
  auto at = [&](const std::string& name) {
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) return row[i];
    ADD_FAILURE() << "no column " << name;
    return 0.0;
  };
  EXPECT_EQ(at("time_s"), 0.25);
  EXPECT_EQ(at("step"), 40.0);
  EXPECT_EQ(at("traction_force_N"), 3.0);
  EXPECT_EQ(at("drawbar_pull_N"), -2.0);
  EXPECT_EQ(at("contact_force_x_N"), 7.0);
  EXPECT_EQ(at("contact_force_z_N"), 11.0);
  EXPECT_EQ(at("rim_longitudinal_force_N"), 13.0);
  EXPECT_EQ(at("rm2_Nm"), 17.0);
  EXPECT_EQ(at("vertical_pressure_force_groove_N"), 9.0);
}

TEST(CouplerExchange, PayloadMeansAndCheckpoint) {
  coupler::ExchangePayload p;
  p.forwarding_s = 0.5, p.nodes_sent = 12, p.facets_sent = 6, p.loaded_nodes = 3;
  const nlohmann::json per = p.per_exchange(4);
  EXPECT_EQ(per["mean_surface_nodes_per_step"], 3.0);
  EXPECT_EQ(per["mean_surface_facets_per_step"], 1.5);
  EXPECT_EQ(per["mean_loaded_nodes_per_step"], 0.75);
  EXPECT_EQ(p.per_exchange(0)["mean_surface_nodes_per_step"], 0.0);

  coupler::SurfacePositions s;
  s.x_m = {1, 2}, s.y_m = {3, 4}, s.z_m = {5, 6};
  const std::string path = test_support::scratch("coupler_exchange") + "/exchange.ckpt";
  cosim::CheckpointWriter out("coupler", 7, 4, 1.0);
  p.save(out, "coupler.");
  s.save(out, "coupler.");
  out.commit(path);
  const cosim::CheckpointReader in(path);
  EXPECT_EQ(in.get_value<double>("coupler.nodes_sent"), 12.0);
  coupler::ExchangePayload q;
  q.restore(in, "coupler.");
  EXPECT_EQ(q.forwarding_s, 0.5);
  EXPECT_EQ(q.loaded_nodes, 3.0);
  coupler::SurfacePositions r;
  r.x_m.resize(2), r.y_m.resize(2), r.z_m.resize(2);
  r.restore(in, "coupler.");
  EXPECT_EQ(r.z_m, s.z_m);
  coupler::SurfacePositions other_mesh;
  other_mesh.x_m.resize(3), other_mesh.y_m.resize(3), other_mesh.z_m.resize(3);
  EXPECT_THROW(other_mesh.restore(in, "coupler."), cosim::Error);  // a checkpoint of another surface
}
