// A study's report.html opened in a real browser (Debian's chromium, headless,
// as a user opens it from disk, offline): every figure decodes and every table
// is there. The page marks on <body> how many of its images loaded
// (data-figures-loaded="k/n", counted by the browser after the load event)
// and how many tables it holds; the test reads the DOM the browser ends with.
// Also what the study writes beside it: one table row per run of a case in a
// pass, the orderings and the checks. Exact expectations: counts and labels.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "test_paths.hpp"

namespace {

using test_support::bin;
using test_support::shell;

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(StudyReport, OpensInAHeadlessBrowserWithEveryFigureAndTable) {
  const auto dir = test_support::scratch("study_report");
  const std::string study = "OMP_NUM_THREADS=1 " + bin() + "/cosim study " + test_support::source_dir() +
                            "/tests/launcher/test_study_report.textproto --out " + dir + " --no-vtk";
  // One pass, then the other: the tables join what completed in DIR.
  auto [code, out] = shell(study + " --pass coarse");
  ASSERT_EQ(code, 0) << out;
  EXPECT_EQ(count(read(dir + "/table.csv"), "\n"), 3u) << "header and the coarse pass's two runs";
  EXPECT_NE(read(dir + "/error_vs_runtime.csv").find(",fine (not run),"), std::string::npos);
  // One case of the fine pass (--case): the coarse run of that case has its
  // reference, the other's still has none.
  std::tie(code, out) = shell(study + " --pass fine --case 5ms");
  ASSERT_EQ(code, 0) << out;
  EXPECT_EQ(out.find("'10ms'"), std::string::npos) << "--case 5ms ran the other case: " << out;
  std::string errors = read(dir + "/error_vs_runtime.csv");
  EXPECT_NE(errors.find("10ms,final_front_m,coarse,"), std::string::npos) << errors;
  EXPECT_NE(errors.find(",fine (not run),"), std::string::npos) << errors;
  EXPECT_TRUE(std::regex_search(errors, std::regex("\n5ms,final_front_m,coarse,[^,]+,[^,]+,fine,[0-9.e-]+,")))
      << errors;
  std::tie(code, out) = shell(study + " --pass fine --resume");
  ASSERT_EQ(code, 0) << out;
  EXPECT_EQ(out.find("pass 'coarse'"), std::string::npos) << "--pass fine ran the coarse pass: " << out;
  EXPECT_NE(out.find("'5ms' completed before"), std::string::npos) << out;
  EXPECT_EQ(read(dir + "/error_vs_runtime.csv").find("(not run)"), std::string::npos);
  std::tie(code, out) = shell(study + " --case 20ms");
  EXPECT_NE(code, 0);
  EXPECT_NE(out.find("--case 20ms: the study's cases are 5ms 10ms"), std::string::npos) << out;
  // --tabulate runs nothing and rewrites the same table.
  const std::string before = read(dir + "/table.csv");
  std::filesystem::remove(dir + "/table.csv");
  std::tie(code, out) = shell(study + " --tabulate");
  ASSERT_EQ(code, 0) << out;
  EXPECT_EQ(out.find("case 1/2"), std::string::npos) << "--tabulate ran a case: " << out;
  EXPECT_EQ(read(dir + "/table.csv"), before);
  std::tie(code, out) = shell(study + " --pass medium");
  EXPECT_NE(code, 0);
  EXPECT_NE(out.find("--pass medium: the study's passes are coarse fine"), std::string::npos) << out;
  // Four runs (two grid cases in two passes), a pass column and the parameter.
  const std::string table = read(dir + "/table.csv");
  EXPECT_EQ(table.rfind("case,pass,end_time_s,", 0), 0u) << table;
  EXPECT_EQ(count(table, "\n"), 5u) << table;
  EXPECT_NE(read(dir + "/orderings.csv").find("front_advances,the surge front advances with time,Martin & Moyce 1952,coarse,1 of 1 hold"),
            std::string::npos);
  const std::string checks = read(dir + "/thesis_comparison.csv");
  const auto coarse_check = checks.find("front at 5 ms,\"Martin & Moyce 1952, Fig. 2: Z / a = 1 at T = 0.09\",coarse,0.05715,");
  ASSERT_NE(coarse_check, std::string::npos) << checks;
  EXPECT_NE(checks.substr(coarse_check, checks.find('\n', coarse_check) - coarse_check).find(",yes,"), std::string::npos)
      << checks;
  EXPECT_TRUE(std::filesystem::exists(dir + "/coarse_front_vs_time.png"));
  errors = read(dir + "/error_vs_runtime.csv");
  EXPECT_NE(errors.find("5ms,final_front_m,coarse,"), std::string::npos) << errors;

  if (std::system("command -v chromium >/dev/null 2>&1") != 0)
    GTEST_FAIL() << "chromium is not installed (scripts/setup.sh installs it)";
  const std::string profile = test_support::scratch("study_report_browser");
  auto [browser, dom] = shell(
      "chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking "
      "--disable-component-update --disable-sync --user-data-dir=" + profile +
      " --virtual-time-budget=10000 --dump-dom file://" + dir + "/report.html 2>/dev/null");
  ASSERT_EQ(browser, 0) << dom;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("data-figures-loaded=\"(\\d+)/(\\d+)\""))) << dom.substr(0, 2000);
  // Per pass: front.png and front_vs_time.png (from each run's front.csv); and the
  // passes' error plot: five figures.
  EXPECT_EQ(m[2], "5") << dom.substr(0, 2000);
  EXPECT_EQ(m[1], m[2]) << "figures that did not load";
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("data-tables=\"(\\d+)\"")));
  std::smatch expected;
  ASSERT_TRUE(std::regex_search(dom, expected, std::regex("data-tables-expected=\"(\\d+)\"")));
  EXPECT_EQ(m[1], expected[1]);
  EXPECT_EQ(expected[1], "4");  // table, error against run time, thesis comparison, orderings
}

}  // namespace
