// Abaqus input-deck export of a cross-section (the inverse of the import): lets a
// generated section be inspected or edited in Abaqus/CAE or other pre-processors,
// and provides the example deck of the tests.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cosim/error.hpp"
#include "tyre_fe/geometry.hpp"

namespace tyre_fe {
namespace {

std::string upper_name(const char* name) {
  std::string s(name);
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// Writes ids 16 to a line (the Abaqus limit for set data lines).
void write_id_list(std::ofstream& out, const std::vector<int>& ids) {
  for (size_t i = 0; i < ids.size(); ++i) {
    out << ids[i];
    out << ((i + 1) % 16 == 0 || i + 1 == ids.size() ? "\n" : ", ");
  }
}

}  // namespace

void write_abaqus_cross_section(const CrossSection& section, const std::string& inp_path) {
  const std::string tmp = inp_path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw cosim::Error("cannot write Abaqus deck '" + tmp + "'");
    out << "** Tyre cross-section written by tyre_fe::write_abaqus_cross_section\n"
        << "** Axisymmetric: x = r (distance from the spin axis), y = axial [m].\n"
        << "** Regions are the ELSETs; NSET RIM = nodes held by the rim; SURFACE\n"
        << "** INNER_LINER = faces loaded by the inflation pressure.\n"
        << "*HEADING\n"
        << "tyre_fe cross-section\n"
        << "*NODE\n";
    char buf[128];
    for (size_t i = 0; i < section.nodes.size(); ++i) {
      std::snprintf(buf, sizeof buf, "%zu, %.17g, %.17g\n", i + 1, section.nodes[i].x(), section.nodes[i].y());
      out << buf;
    }
    out << "*ELEMENT, TYPE=CGAX4R\n";
    for (size_t q = 0; q < section.quads.size(); ++q) {
      const auto& n = section.quads[q];
      out << q + 1 << ", " << n[0] + 1 << ", " << n[1] + 1 << ", " << n[2] + 1 << ", " << n[3] + 1 << "\n";
    }
    for (int r = 0; r < kRegionCount; ++r) {
      std::vector<int> ids;
      for (size_t q = 0; q < section.quads.size(); ++q)
        if (static_cast<int>(section.quad_region[q]) == r) ids.push_back(static_cast<int>(q) + 1);
      if (ids.empty()) continue;
      out << "*ELSET, ELSET=" << upper_name(region_name(static_cast<Region>(r))) << "\n";
      write_id_list(out, ids);
    }
    std::vector<int> rim;
    for (int n : section.rim_nodes) rim.push_back(n + 1);
    if (!rim.empty()) {
      out << "*NSET, NSET=RIM\n";
      write_id_list(out, rim);
    }
    if (section.tread_centre_node >= 0)
      out << "*NSET, NSET=TREAD_CENTRE\n" << section.tread_centre_node + 1 << "\n";
    if (!section.inner_liner_edges.empty()) {
      out << "*SURFACE, NAME=INNER_LINER, TYPE=ELEMENT\n";
      for (const auto& e : section.inner_liner_edges) out << e[0] + 1 << ", S" << e[1] + 1 << "\n";
    }
    out.flush();
    if (!out) throw cosim::Error("error writing Abaqus deck '" + tmp + "'");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, inp_path, ec);
  if (ec) throw cosim::Error("cannot rename '" + tmp + "' to '" + inp_path + "': " + ec.message());
}

}  // namespace tyre_fe
