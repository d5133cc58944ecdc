// Coarser copies of a mesh by quadric edge collapses (core/mesh/mesh_decimate.h): on real meshes (the Venus and the
// Nefertiti bust, open below) the result indexes the input's vertices, reaches about the target, keeps every
// boundary vertex and turns no triangle over; refusals give the input back.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "core/mesh/mesh_decimate.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

glm::dvec3 face_normal(const TriMesh& m, const glm::uvec3& t) {
  return glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
}

// Vertices on an edge used by one triangle only.
std::set<unsigned> boundary_vertices(const std::vector<glm::uvec3>& triangles) {
  std::map<std::pair<unsigned, unsigned>, int> edges;
  for (const glm::uvec3& t : triangles)
    for (int c = 0; c < 3; ++c) {
      const unsigned a = t[c], b = t[(c + 1) % 3];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  std::set<unsigned> out;
  for (const auto& [e, n] : edges)
    if (n == 1) out.insert(e.first), out.insert(e.second);
  return out;
}

// Decimates `mesh` to a quarter of its vertices and checks the result.
void check_quarter(const TriMesh& mesh, const char* name) {
  SCOPED_TRACE(name);
  const std::set<unsigned> rim = boundary_vertices(mesh.triangles);
  const std::size_t target = mesh.vertex_count() / 4;
  const std::vector<glm::uvec3> coarse = decimated_triangles(mesh, target);
  const std::size_t used = used_vertex_count(coarse, mesh.vertex_count());
  EXPECT_LE(used, std::max(target + target / 10, rim.size())) << "of " << mesh.vertex_count();
  EXPECT_LT(coarse.size(), mesh.triangle_count() / 2);
  std::set<unsigned> kept;
  for (const glm::uvec3& t : coarse) kept.insert({t.x, t.y, t.z});
  for (unsigned v : rim) EXPECT_TRUE(kept.count(v)) << "boundary vertex " << v << " was collapsed";
  EXPECT_EQ(boundary_vertices(coarse).size(), rim.size()) << "the rims stay and no hole opens";
  // No triangle turned over: each coarse triangle faces like the input's triangles around its corners.
  std::vector<glm::dvec3> vertex_normal(mesh.vertex_count(), glm::dvec3(0.0));
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) vertex_normal[t[c]] += face_normal(mesh, t);
  std::size_t flipped = 0;
  for (const glm::uvec3& t : coarse)
    flipped += glm::dot(face_normal(mesh, t), vertex_normal[t.x] + vertex_normal[t.y] + vertex_normal[t.z]) < 0.0;
  EXPECT_LE(flipped, coarse.size() / 100) << flipped << " of " << coarse.size() << " triangles face inwards";
  EXPECT_EQ(decimated_triangles(mesh, target), coarse) << "deterministic";
}

TEST(MeshDecimate, RealMeshesAtAQuarterKeepTheirRimsAndFacing) {
  const std::filesystem::path data = std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data";
  const TriMesh venus = load_mesh(data / "venus.obj");
  check_quarter(venus, "venus");
  const TriMesh bust = load_mesh(data / "nefertiti.off");
  ASSERT_FALSE(boundary_vertices(bust.triangles).empty()) << "the bust is open below";
  check_quarter(bust, "nefertiti");
}

TEST(MeshDecimate, WhatCannotBeReducedComesBackWhole) {
  TriMesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_EQ(decimated_triangles(quad, 4), quad.triangles) << "target ≥ #V";
  EXPECT_EQ(decimated_triangles(quad, 2), quad.triangles) << "every vertex on the boundary";
  TriMesh fan = quad;  // three triangles on one edge: not a manifold, OpenMesh refuses the third
  fan.positions.push_back({0.5, 0.5, 1});
  fan.triangles.push_back({0, 2, 4});
  EXPECT_EQ(decimated_triangles(fan, 3), fan.triangles);
  EXPECT_EQ(used_vertex_count(fan.triangles, fan.vertex_count()), 5u);
}

}  // namespace
}  // namespace trispline::core
