// What a study reads from its runs (launcher/study_table.hpp, study_report.hpp):
// the thesis's orderings (tests/data/torque_force_orderings.csv, each with its
// thesis line and figure) evaluated into hold / fail, and the checks against a
// thesis number (a run's result, the slip where a curve crosses zero, the slip
// of its largest or smallest value). The expected outcomes are worked out by
// hand from the few made-up rows of each test; they are exact (no tolerance):
// the evaluation compares and interpolates the given numbers, nothing more.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>

#include "cosim/error.hpp"
#include "cosim/scene_io.hpp"
#include "study.hpp"
#include "study_report.hpp"
#include "study_table.hpp"
#include "test_paths.hpp"

namespace {

using cosim::StudyRow;

StudyRow run(const std::string& label, std::map<std::string, std::string> parameters, nlohmann::json results) {
  StudyRow r;
  r.label = label, r.parameters = std::move(parameters);
  r.summary = {{"results", std::move(results)}, {"wall_time_s", 10.0}};
  return r;
}

cosim::Ordering ordering(const std::string& quantity, const std::string& kind, const std::string& column,
                         const std::string& order, const std::string& where = "") {
  return {"id", "claim", "source", quantity, kind, column, order, where, "here"};
}

// Every ordering of the thesis reads, and each compares at least one pair (or
// run) among the torque study's cases: a value or column the study does not run
// would leave the ordering "not run" for ever. Every result is set to 1 here (a
// positive drawbar pull passes the driving-state filter); which way each
// comparison goes does not matter for this test.
TEST(StudyOrderings, EveryThesisOrderingHasRunsToCompareInTheTorqueStudy) {
  const auto list = cosim::read_orderings(test_support::data_dir() + "/torque_force_orderings.csv");
  ASSERT_GE(list.size(), 15u);
  const auto study = cosim::load_study(test_support::source_dir() + "/configs/studies/torque_force.textproto");
  const auto cases = cosim::expand_cases(study->message);
  // 3 treads x 2 snows x 4 torques + 4 at 6000 N on the frictionless floor, + 2 treads x 2 torques on frozen ground
  ASSERT_EQ(cases.size(), 32u);
  std::vector<StudyRow> rows;
  nlohmann::json ones;
  for (const char* q : {"sinkage_m", "traction_minus_rrf_N", "rolling_resistance_force_N", "groove_force_N",
                        "net_longitudinal_pressure_force_N", "drawbar_pull_N"})
    ones[q] = 1.0;
  for (const auto& k : cases) {
    std::map<std::string, std::string> p;
    for (const auto& s : k.parameter()) p[s.substr(0, s.find('='))] = s.substr(s.find('=') + 1);
    rows.push_back(run(k.label(), p, ones));
  }
  for (const auto& o : list) {
    const auto r = cosim::evaluate_ordering(o, rows);
    EXPECT_GT(r.compared, 0) << o.location << " " << o.id << ": " << r.ours;
    for (const auto& row : rows) EXPECT_FALSE(std::isnan(cosim::row_number(row, o.quantity))) << o.id;
  }
}

TEST(StudyOrderings, OrderRanksWithinGroupsThatDifferOnlyInTheColumn) {
  // Two snows, two treads: block > smooth holds in soft (0.06 > 0.05), fails in hard (0.03 < 0.04).
  const std::vector<StudyRow> rows{run("a", {{"tread", "block"}, {"snow", "soft"}}, {{"sinkage_m", 0.06}}),
                                   run("b", {{"tread", "smooth"}, {"snow", "soft"}}, {{"sinkage_m", 0.05}}),
                                   run("c", {{"tread", "block"}, {"snow", "hard"}}, {{"sinkage_m", 0.03}}),
                                   run("d", {{"tread", "smooth"}, {"snow", "hard"}}, {{"sinkage_m", 0.04}})};
  auto r = cosim::evaluate_ordering(ordering("sinkage_m", "order", "tread", "block>smooth"), rows);
  EXPECT_EQ(r.compared, 2);
  EXPECT_EQ(r.held, 1);
  EXPECT_EQ(r.hold, "fail");
  EXPECT_EQ(r.ours.rfind("1 of 2 hold; hard: block 0.03 <= smooth 0.04", 0), 0u) << r.ours;
  // Restricted to soft snow it holds.
  r = cosim::evaluate_ordering(ordering("sinkage_m", "order", "tread", "block>smooth", "snow=soft"), rows);
  EXPECT_EQ(r.hold, "hold");
  EXPECT_EQ(r.compared, 1);
  // A chain a > b > c compares adjacent pairs; a value no run has is skipped.
  const std::vector<StudyRow> chain{run("s", {{"tread", "smooth"}}, {{"f", 3.0}}), run("k", {{"tread", "block"}}, {{"f", 1.0}}),
                                    run("p", {{"tread", "block_sipes"}}, {{"f", 2.0}})};
  r = cosim::evaluate_ordering(ordering("f", "order", "tread", "smooth>block_sipes>block>rib"), chain);
  EXPECT_EQ(r.compared, 2);
  EXPECT_EQ(r.hold, "hold");
}

TEST(StudyOrderings, IncreasingSignsFiltersAndDifferences) {
  // Traction minus RRF at 0, 200, 400 N m: -50, 100, 90 (falls at the last step).
  std::vector<StudyRow> rows;
  const double f3[] = {10, 200, 240}, f5[] = {60, 100, 150};
  for (int i = 0; i < 3; ++i)
    rows.push_back(run("t" + std::to_string(i), {{"torque_Nm", std::to_string(200 * i)}},
                       {{"traction_force_N", f3[i]}, {"rolling_resistance_force_N", f5[i]}}));
  const std::string q = "traction_force_N-rolling_resistance_force_N";
  EXPECT_DOUBLE_EQ(cosim::row_number(rows[0], q), -50.0);
  auto r = cosim::evaluate_ordering(ordering(q, "increasing", "torque_Nm", ""), rows);
  EXPECT_EQ(r.compared, 2);
  EXPECT_EQ(r.held, 1);
  EXPECT_EQ(cosim::evaluate_ordering(ordering(q, "negative", "", "", "torque_Nm=0"), rows).hold, "hold");
  EXPECT_EQ(cosim::evaluate_ordering(ordering(q, "positive", "", "", "torque_Nm>0"), rows).hold, "hold");
  EXPECT_EQ(cosim::evaluate_ordering(ordering(q, "negative", "", "", "torque_Nm>=200"), rows).hold, "fail");
  EXPECT_EQ(cosim::evaluate_ordering(ordering(q, "negative", "", "", "torque_Nm>600"), rows).hold, "not run");
  EXPECT_THROW(cosim::row_matches(rows[0], "torque_Nm~3"), cosim::Error);
  EXPECT_THROW(cosim::row_matches(rows[0], "torque_Nm>abc"), cosim::Error);
}

TEST(StudyOrderings, ABadOrderingNamesItsFileLineAndField) {
  const auto dir = test_support::scratch("study_orderings_bad");
  std::ofstream(dir + "/o.csv") << "id,claim,source,quantity,kind,column,order,where\n"
                                << "a,\"x, y\",s,sinkage_m,order,tread,block>smooth,\n"
                                << "b,claim,s,sinkage_m,bigger,tread,,\n";
  try {
    cosim::read_orderings(dir + "/o.csv");
    FAIL() << "a bad kind was accepted";
  } catch (const cosim::Error& e) {
    EXPECT_NE(std::string(e.what()).find("o.csv:3: field kind"), std::string::npos) << e.what();
  }
}

TEST(StudyChecks, CaseResultZeroCrossingAndExtremes) {
  // Drawbar pull against slip: -300 at 0.4, +100 at 0.8, +50 at 0.9: zero at
  // 0.4 + 0.4 * 300 / 400 = 0.7, largest at 0.8.
  const std::vector<StudyRow> rows{run("s40", {{"phase", "slip"}}, {{"dbp", -300.0}, {"s", 0.4}}),
                                   run("s80", {{"phase", "slip"}}, {{"dbp", 100.0}, {"s", 0.8}}),
                                   run("s90", {{"phase", "slip"}}, {{"dbp", 50.0}, {"s", 0.9}}),
                                   run("towed", {{"phase", "towed"}}, {{"dbp", 900.0}, {"s", -0.2}, {"rm2", 54.0}})};
  cosim::scene::StudyCheck c;
  c.set_kind(cosim::scene::StudyCheck::ZERO_CROSSING);
  c.set_x("s"), c.set_result("dbp"), c.set_value(0.65), c.set_tolerance(0.1), c.set_where("phase=slip");
  auto r = cosim::evaluate_check(c, rows);
  EXPECT_NEAR(r.ours, 0.7, 1e-15);
  EXPECT_EQ(r.agrees, "yes");
  c.set_kind(cosim::scene::StudyCheck::ARG_MAX), c.set_value(0.6);
  r = cosim::evaluate_check(c, rows);
  EXPECT_EQ(r.ours, 0.8);  // the towed run is filtered out
  EXPECT_EQ(r.agrees, "no");
  // Without the 0.9 run the largest is the last run's: no maximum inside the range.
  r = cosim::evaluate_check(c, {rows[0], rows[1]});
  EXPECT_EQ(r.ours, 0.8);
  EXPECT_EQ(r.agrees, "no");
  c.set_kind(cosim::scene::StudyCheck::CASE_RESULT), c.set_case_label("towed"), c.set_result("rm2");
  c.set_value(45.0), c.set_tolerance(0.25);
  r = cosim::evaluate_check(c, rows);
  EXPECT_DOUBLE_EQ(r.difference, 0.2);  // (54 - 45) / 45
  EXPECT_EQ(r.agrees, "yes");
  c.set_case_label("absent");
  EXPECT_EQ(cosim::evaluate_check(c, rows).agrees, "not run");
}

// F5 = RRM / r with the reference run's measured radius: a run whose coupler
// used r = 0.36 m (RRM 90 N m: F5 = 250 N) recomputed with the free-rolling
// run's 0.4 m gives F5 = 225 N, so its drawbar pull rises by 25 N and F3 - F5
// is F3 - 225. Hand arithmetic, exact to rounding (1e-12).
TEST(StudyF5Radius, RecomputesTheForcesWithTheReferenceRunsRadius) {
  auto driven = [](const std::string& tread, const std::string& torque, double r) {
    return run(tread + torque, {{"tread", tread}, {"torque_Nm", torque}},
               {{"rolling_resistance_moment_Nm", 90.0}, {"rolling_resistance_force_N", 250.0},
                {"traction_force_N", 400.0}, {"drawbar_pull_N", -100.0}, {"tyre", {{"rolling_radius_m", r}}}});
  };
  std::vector<StudyRow> rows{driven("smooth", "0", 0.4), driven("smooth", "600", 0.2), driven("block", "600", 0.3)};
  cosim::scene::StudyF5Radius f;
  f.set_column("torque_Nm"), f.set_value("0");
  cosim::apply_f5_radius(f, rows);
  for (int i : {0, 1}) {
    EXPECT_NEAR(cosim::row_number(rows[i], "rolling_radius_for_F5_m"), 0.4, 1e-15);
    EXPECT_NEAR(cosim::row_number(rows[i], "rolling_resistance_force_N"), 225.0, 1e-12);
    EXPECT_NEAR(cosim::row_number(rows[i], "drawbar_pull_N"), -75.0, 1e-12);
    EXPECT_NEAR(cosim::row_number(rows[i], "traction_minus_rrf_N"), 175.0, 1e-12);
  }
  // The block has no free-rolling run: it keeps its own.
  EXPECT_TRUE(std::isnan(cosim::row_number(rows[2], "rolling_radius_for_F5_m")));
  EXPECT_EQ(cosim::row_number(rows[2], "drawbar_pull_N"), -100.0);
  // One reference case for all.
  cosim::scene::StudyF5Radius one;
  one.set_case_label("block600");
  std::vector<StudyRow> again{driven("smooth", "0", 0.4), driven("block", "600", 0.3)};
  cosim::apply_f5_radius(one, again);
  EXPECT_NEAR(cosim::row_number(again[0], "rolling_resistance_force_N"), 300.0, 1e-12);
}

}  // namespace
