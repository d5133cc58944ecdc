// Checks shared by the primitive tests: validity, unit normals, closedness (every undirected edge used by exactly two
// triangles, in opposite directions).
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "core/mesh/mesh_io.h"

namespace trispline::core::test {

inline void expect_valid_with_unit_normals(const TriMesh& m, const std::string& what) {
  EXPECT_NO_THROW(validate_mesh(m, what));
  ASSERT_EQ(m.normals.size(), m.positions.size()) << what;
  for (std::size_t i = 0; i < m.normals.size(); ++i)
    ASSERT_NEAR(glm::length(m.normals[i]), 1.0, 1e-9) << what << " vertex " << i;
}

// Number of directed edges (a→b) that appear more than once or whose reverse is missing: 0 for a closed,
// consistently oriented, edge-manifold mesh.
inline int orientation_defects(const TriMesh& m, int* boundary = nullptr) {
  std::map<std::pair<unsigned, unsigned>, int> directed;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  int defects = 0, open = 0;
  for (const auto& [e, n] : directed) {
    if (n > 1) defects += n - 1;
    if (!directed.count({e.second, e.first})) ++open;
  }
  if (boundary) *boundary = open;
  return defects + (boundary ? 0 : open);
}

}  // namespace trispline::core::test
