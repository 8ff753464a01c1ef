// The one legacy VTK writer (common/include/cosim/vtk.hpp) against the legacy
// format as the VTK file-format document specifies it ("Simple Legacy Formats",
// https://docs.vtk.org/en/latest/vtk_file_formats/vtk_legacy_file_format.html):
// the five parts in order, binary values big-endian right after the newline of
// their keyword line. The expected files are spelled out byte by byte here, the
// numbers as their IEEE 754 bit patterns written by hand (1.0f = 3F800000, ...),
// not computed with the writer's encoders.
//
// Tolerance: none. The format is an exact encoding, and every number below is
// exactly representable in the precision it is written in (except the one test
// that checks float rounding, whose expected pattern is IEEE 754's
// round-to-nearest of 0.1), so any byte that differs is a defect.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cosim/error.hpp"
#include "cosim/vtk.hpp"
#include "test_paths.hpp"

namespace {

using cosim::vtk::CellType;
using cosim::vtk::LegacyFile;
using cosim::vtk::Real;
using On = LegacyFile::On;

// Bytes from a list of values 0..255.
std::string b(std::initializer_list<int> bytes) {
  std::string s;
  for (int v : bytes) s.push_back(static_cast<char>(v));
  return s;
}

using test_support::read_file;

TEST(Vtk, BigEndianEncodersMatchIeee754BitPatterns) {
  std::string out;
  cosim::vtk::put_be_int32(out, 258);  // 0x00000102
  cosim::vtk::put_be_int32(out, -1);   // two's complement: FFFFFFFF
  EXPECT_EQ(out, b({0x00, 0x00, 0x01, 0x02, 0xFF, 0xFF, 0xFF, 0xFF}));
  out.clear();
  cosim::vtk::put_be_float32(out, 1.0);   // 3F800000
  cosim::vtk::put_be_float32(out, -2.0);  // C0000000
  cosim::vtk::put_be_float32(out, 0.1);   // nearest float to 0.1: 3DCCCCCD
  EXPECT_EQ(out, b({0x3F, 0x80, 0x00, 0x00, 0xC0, 0x00, 0x00, 0x00, 0x3D, 0xCC, 0xCC, 0xCD}));
  out.clear();
  cosim::vtk::put_be_float64(out, 1.0);  // 3FF0000000000000
  cosim::vtk::put_be_float64(out, 0.1);  // 3FB999999999999A
  EXPECT_EQ(out, b({0x3F, 0xF0, 0, 0, 0, 0, 0, 0, 0x3F, 0xB9, 0x99, 0x99, 0x99, 0x99, 0x99, 0x9A}));
}

// Two particles as a POLYDATA point cloud of floats: POINTS, VERTICES (each
// cell "1 i"), POINT_DATA with one scalar and one vector field.
TEST(Vtk, PointCloudIsTheLegacyPolyDataLayout) {
  const double x[] = {1.0, 0.0}, y[] = {0.0, 0.5}, z[] = {-2.0, 1.0};
  const double density[] = {1.0, 2.0};
  const double vx[] = {0.0, 1.0}, vy[] = {0.5, 0.0}, vz[] = {0.0, -2.0};
  auto file = LegacyFile::poly_data("two particles", Real::Float32);
  file.points(2, x, y, z);
  file.vertices();
  file.scalars(On::Points, "density", density);
  file.vectors(On::Points, "velocity", vx, vy, vz);

  const std::string f1 = b({0x3F, 0x80, 0, 0}), f0 = b({0, 0, 0, 0}), fm2 = b({0xC0, 0, 0, 0}),
                    fh = b({0x3F, 0, 0, 0}), f2 = b({0x40, 0, 0, 0});
  const std::string i0 = b({0, 0, 0, 0}), i1 = b({0, 0, 0, 1});
  const std::string expected = "# vtk DataFile Version 3.0\ntwo particles\nBINARY\nDATASET POLYDATA\n"
                               "POINTS 2 float\n" + f1 + f0 + fm2 + f0 + fh + f1 + "\n"
                               "VERTICES 2 4\n" + i1 + i0 + i1 + i1 + "\n"
                               "POINT_DATA 2\n"
                               "SCALARS density float 1\nLOOKUP_TABLE default\n" + f1 + f2 + "\n"
                               "VECTORS velocity float\n" + f0 + fh + f0 + f1 + f0 + fm2 + "\n";
  EXPECT_EQ(file.bytes(), expected);
}

// One quad as an UNSTRUCTURED_GRID of doubles: CELLS (size = cells x (1 + 4)),
// CELL_TYPES (VTK_QUAD = 9), CELL_DATA before POINT_DATA (the document: "It does
// not matter whether POINT_DATA or CELL_DATA comes first"), an int scalar.
TEST(Vtk, QuadIsTheLegacyUnstructuredGridLayout) {
  const double x[] = {0.0, 1.0, 1.0, 0.0}, y[] = {0.0, 0.0, 1.0, 1.0}, z[] = {0.0, 0.0, 0.0, 0.0};
  auto file = LegacyFile::unstructured_grid("one quad", Real::Float64);
  file.points(4, x, y, z);
  file.cells({0, 1, 2, 3}, 4, CellType::Quad);
  file.int_scalars(On::Cells, "region", {7});
  file.scalars(On::Points, "p", std::vector<double>{0.0, 1.0, 1.0, 0.0});

  const std::string d0 = b({0, 0, 0, 0, 0, 0, 0, 0}), d1 = b({0x3F, 0xF0, 0, 0, 0, 0, 0, 0});
  auto i = [](int v) { return b({0, 0, 0, v}); };
  const std::string expected = "# vtk DataFile Version 3.0\none quad\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
                               "POINTS 4 double\n" + d0 + d0 + d0 + d1 + d0 + d0 + d1 + d1 + d0 + d0 + d1 + d0 + "\n"
                               "CELLS 1 5\n" + i(4) + i(0) + i(1) + i(2) + i(3) + "\n"
                               "CELL_TYPES 1\n" + i(9) + "\n"
                               "CELL_DATA 1\n"
                               "SCALARS region int 1\nLOOKUP_TABLE default\n" + i(7) + "\n"
                               "POINT_DATA 4\n"
                               "SCALARS p double 1\nLOOKUP_TABLE default\n" + d0 + d1 + d1 + d0 + "\n";
  EXPECT_EQ(file.bytes(), expected);
}

TEST(Vtk, HexahedronCellTypeIs12) {
  std::vector<double> x(8, 0.0);
  auto file = LegacyFile::unstructured_grid("hex", Real::Float64);
  file.points(8, x.data(), x.data(), x.data());
  file.cells({0, 1, 2, 3, 4, 5, 6, 7}, 8, CellType::Hexahedron);
  const std::string& s = file.bytes();
  const std::string types = "CELL_TYPES 1\n";
  ASSERT_NE(s.find("CELLS 1 9\n"), std::string::npos);  // 1 cell x (1 count + 8 ids)
  const auto at = s.find(types);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(s.substr(at + types.size(), 5), b({0, 0, 0, 12}) + "\n");
}

TEST(Vtk, MisuseIsRefused) {
  const double x[] = {0.0, 1.0};
  auto cloud = LegacyFile::poly_data("t", Real::Float32);
  cloud.points(2, x, x, x);
  EXPECT_THROW(cloud.cells({0, 1}, 2, CellType::Quad), cosim::Error);          // CELLS in POLYDATA
  EXPECT_THROW(cloud.scalars(On::Points, "bad name", x), cosim::Error);         // blank in a name
  EXPECT_THROW(cloud.scalars(On::Points, "p", std::vector<double>{1.0}), cosim::Error);  // 1 value, 2 points
  EXPECT_THROW(cloud.vectors(On::Points, "v", std::vector<double>(5, 0.0)), cosim::Error);
  auto grid = LegacyFile::unstructured_grid("t", Real::Float64);
  grid.points(2, x, x, x);
  EXPECT_THROW(grid.vertices(), cosim::Error);                                  // VERTICES in a grid
  EXPECT_THROW(grid.cells({0, 1, 0}, 2, CellType::Quad), cosim::Error);        // 3 ids, cells of 2
  EXPECT_THROW(LegacyFile::poly_data("two\nlines", Real::Float32), cosim::Error);  // title is one line
  EXPECT_THROW(LegacyFile::poly_data(std::string(257, 't'), Real::Float32), cosim::Error);  // <= 256 chars
}

// The series: numbered files and ParaView's .vtk.series index (JSON with
// "file-series-version" "1.0" and the files with their times), no .tmp left.
TEST(Vtk, SeriesWritesNumberedFramesAndTheIndex) {
  const std::string dir = test_support::scratch("vtk_series");
  const double x[] = {0.25};
  cosim::vtk::Series series(dir + "/frames", "cloud");
  for (double t : {0.0, 0.5}) {
    auto file = LegacyFile::poly_data("cloud", Real::Float32);
    file.points(1, x, x, x);
    file.vertices();
    series.write(t, file);
  }
  EXPECT_EQ(series.frames(), 2u);
  const auto index = nlohmann::json::parse(read_file(dir + "/frames/cloud.vtk.series"));
  EXPECT_EQ(index["file-series-version"], "1.0");
  ASSERT_EQ(index["files"].size(), 2u);
  EXPECT_EQ(index["files"][0]["name"], "cloud_00000.vtk");
  EXPECT_EQ(index["files"][1]["name"], "cloud_00001.vtk");
  EXPECT_EQ(index["files"][1]["time"], 0.5);
  const std::string frame = read_file(dir + "/frames/cloud_00001.vtk");
  EXPECT_EQ(frame.rfind("# vtk DataFile Version 3.0\ncloud\nBINARY\n", 0), 0u);
  EXPECT_FALSE(std::filesystem::exists(dir + "/frames/cloud_00001.vtk.tmp"));
  auto file = LegacyFile::poly_data("t", Real::Float32);
  EXPECT_THROW(file.save(dir + "/no_such_folder/x.vtk"), cosim::Error);
}

}  // namespace
