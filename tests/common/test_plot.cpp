// The one gnuplot helper (cosim::plot_png and its wrappers plot_csv and
// plot_csv_map, common/include/cosim/outputs.hpp): a missing or failing gnuplot
// writes nothing and reports false; a present one writes a PNG of the requested
// size. The PNG is checked against the PNG specification (ISO/IEC 15948, W3C
// PNG 2nd ed., sections 5.2 "PNG signature" and 11.2.2 "IHDR"): the 8 signature
// bytes 89 50 4E 47 0D 0A 1A 0A, then the IHDR chunk whose first two fields are
// the width and height as 4-byte big-endian integers. No tolerance: the
// signature and the pixel size are exact by the specification.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cosim/outputs.hpp"
#include "test_paths.hpp"

namespace {

bool gnuplot_present() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

using test_support::read_file;

std::uint32_t be32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(s[at + k]);
  return v;
}

std::string write_csv(const std::string& dir, const std::string& name, double scale) {
  const std::string path = dir + "/" + name;
  std::ofstream out(path);
  out << "t,a,b\n";
  for (int i = 1; i <= 10; ++i) out << i << "," << scale * i << "," << scale * i * i << "\n";
  return path;
}

// PATH emptied for the lifetime of the object.
class NoPath {
 public:
  NoPath() : saved_(std::getenv("PATH") ? std::getenv("PATH") : "") { setenv("PATH", "", 1); }
  ~NoPath() { setenv("PATH", saved_.c_str(), 1); }

 private:
  std::string saved_;
};

TEST(Plot, WithoutGnuplotReturnsFalseAndWritesNothing) {
  const std::string dir = test_support::scratch("plot_no_gnuplot");
  const std::string csv = write_csv(dir, "a.csv", 1.0);
  {
    NoPath no_path;
    EXPECT_FALSE(cosim::plot_csv(csv, dir + "/a.png", 1, {{2, "a"}}, "t", "x", "y"));
    EXPECT_FALSE(cosim::plot_csv_map(csv, dir + "/m.png", 1, 2, 3, "t", "x", "y", "v"));
  }
  std::size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.path().filename() != "a.csv";
  EXPECT_EQ(files, 0u) << "no PNG and no gnuplot script may be left";
}

TEST(Plot, FailingGnuplotReturnsFalseAndLeavesNoPng) {
  if (!gnuplot_present()) GTEST_SKIP() << "gnuplot not installed";
  const std::string dir = test_support::scratch("plot_failing");
  // A CSV that does not exist: gnuplot stops with "No data in plot" and a nonzero exit code.
  EXPECT_FALSE(cosim::plot_csv(dir + "/missing.csv", dir + "/a.png", 1, {{2, "a"}}, "t", "x", "y"));
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(Plot, WritesAPngOfTheRequestedSize) {
  if (!gnuplot_present()) GTEST_SKIP() << "gnuplot not installed";
  const std::string dir = test_support::scratch("plot_png");
  const std::string csv = write_csv(dir, "a.csv", 1.0);
  ASSERT_TRUE(cosim::plot_csv(csv, dir + "/a.png", 1, {{2, "a"}, {3, "b"}}, "title", "x", "y"));
  const std::string png = read_file(dir + "/a.png");
  ASSERT_GE(png.size(), 24u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(be32(png, 16), 900u);  // plot_csv's size: 900 x 600
  EXPECT_EQ(be32(png, 20), 600u);
  EXPECT_FALSE(std::filesystem::exists(dir + "/a.png.gp")) << "the gnuplot script is removed";
}

// Titles and labels are the user's text: an apostrophe must not end gnuplot's string.
TEST(Plot, QuotesInTitlesAndLabelsAreDrawn) {
  if (!gnuplot_present()) GTEST_SKIP() << "gnuplot not installed";
  const std::string dir = test_support::scratch("plot_quotes");
  const std::string csv = write_csv(dir, "a.csv", 1.0);
  EXPECT_TRUE(cosim::plot_csv(csv, dir + "/a.png", 1, {{2, "the block's force"}}, "the ribs' depth", "rib's x",
                              "it's y"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/a.png"));
}

// What the study plot and the footprint need: two CSV files in one plot, a log
// axis, expression columns, labels, a colour map, a chosen size.
TEST(Plot, SeveralFilesLogAxesAndExpressionsInOnePlot) {
  if (!gnuplot_present()) GTEST_SKIP() << "gnuplot not installed";
  const std::string dir = test_support::scratch("plot_two_files");
  const std::string a = write_csv(dir, "a.csv", 1.0), b = write_csv(dir, "b.csv", 2.0);
  cosim::PlotOptions o;
  o.title = "two files", o.x_label = "t", o.y_label = "a";
  o.log_x = o.log_y = true, o.width_px = 640, o.height_px = 480;
  ASSERT_TRUE(cosim::plot_png(dir + "/two.png", o,
                              {{a, "1:2", "lines lw 2", "a"},
                               {b, "1:(abs($2)*100)", "linespoints pt 7", "b x 100"},
                               {b, "1:2:1", "labels offset 0,1", ""}}));
  const std::string png = read_file(dir + "/two.png");
  ASSERT_GE(png.size(), 24u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(be32(png, 16), 640u);
  EXPECT_EQ(be32(png, 20), 480u);
  cosim::PlotOptions map;
  map.equal_axes = true, map.colour_label = "kPa";
  EXPECT_TRUE(cosim::plot_png(dir + "/map.png", map, {{a, "1:2:($3/1000)", "points pt 5 palette", ""}}));
}

}  // namespace
