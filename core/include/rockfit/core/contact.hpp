// Which base vertices of the block touch the ground: one vertex or one base edge (docs/design.md §2, §3).
#pragma once

#include <string>

#include "rockfit/core/block.hpp"

namespace rockfit::core {

// Base vertices in contact with the ground: one vertex (second == 0) or a base edge. An empty Contact
// (first == 0) means "no single vertex or edge": after a facet impact that brings the block to rest the
// whole base stays on the ground.
struct Contact {
  int first = 0;
  int second = 0;
  static Contact Vertex(int k) { return {Block::WrapVertex(k), 0}; }
  // The edge between two neighbouring vertices, stored in cyclic order (V1V2, V2V3, V3V4, V4V1), so that
  // Edge(2, 1) == Edge(1, 2). Throws InvalidArgument if i and j are not neighbours.
  static Contact Edge(int i, int j);
  bool is_vertex() const { return first != 0 && second == 0; }
  bool is_edge() const { return first != 0 && second != 0; }
  // "V4" or "V3V4"; "none" when empty.
  std::string ToString() const;
  bool operator==(const Contact& other) const { return first == other.first && second == other.second; }
  bool operator!=(const Contact& other) const { return !(*this == other); }
};

}  // namespace rockfit::core
