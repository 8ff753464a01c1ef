#pragma once
// Private to tyre_fe: a minimal reader of the parts of an Abaqus input deck that
// describe a 2D axisymmetric mesh (see abaqus_import.cpp for what is accepted).
#include <array>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace tyre_fe::detail {

struct AbaqusNode {
  Eigen::Vector2d position;  // (x, y) of the deck = (r, y)
  int line = 0;
};

struct AbaqusElement {
  int id = 0;
  std::array<int, 4> nodes{};  // node ids as written
  int line = 0;
};

struct AbaqusSurfaceFace {
  int element = 0;  // element id
  int face = 0;     // 0..3 for S1..S4 (S_k joins the element's nodes k and k+1)
  int line = 0;
};

struct AbaqusSurface {
  std::vector<AbaqusSurfaceFace> faces;
};

struct AbaqusDeck {
  std::map<int, AbaqusNode> nodes;
  std::vector<int> node_order;  // node ids in the order of the deck
  std::vector<AbaqusElement> elements;
  // Set and surface names upper-cased (Abaqus names are case-insensitive);
  // members in the order first given, without duplicates.
  std::map<std::string, std::vector<int>> elsets;
  std::map<std::string, std::vector<int>> nsets;  // also node-based *SURFACEs
  std::map<std::string, AbaqusSurface> surfaces;  // element-based *SURFACEs
};

// Reads the deck; throws cosim::Error naming path:line for malformed input.
AbaqusDeck read_abaqus_deck(const std::string& path);

}  // namespace tyre_fe::detail
