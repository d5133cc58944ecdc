// Text as a mesh (core/mesh/text_mesh.h): closed and outward, sized by the font, holes kept, errors named.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "core/mesh/text_mesh.h"

using namespace trispline::core;

namespace {

struct Stats {
  Aabb box;
  double volume = 0.0;  // signed, by the divergence theorem
  int unpaired = 0;     // directed edges (welded by exact position) without their reverse once
};

Stats stats_of(const TriMesh& m) {
  Stats s;
  for (const glm::dvec3& p : m.positions) s.box.extend(p);
  std::map<std::array<double, 3>, std::uint32_t> weld;
  std::vector<std::uint32_t> id(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    id[i] = weld.emplace(std::array<double, 3>{m.positions[i].x, m.positions[i].y, m.positions[i].z},
                         static_cast<std::uint32_t>(weld.size()))
                .first->second;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 &a = m.positions[t.x], &b = m.positions[t.y], &c = m.positions[t.z];
    s.volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    for (int k = 0; k < 3; ++k) ++edges[{id[t[k]], id[t[(k + 1) % 3]]}];
  }
  for (const auto& [e, n] : edges) {
    const auto r = edges.find({e.second, e.first});
    if (n != 1 || r == edges.end() || r->second != 1) ++s.unpaired;
  }
  return s;
}

// Area of the front faces (z > 0, normal +z) containing the point (x, y): 0 when it is not covered.
bool front_covers(const TriMesh& m, double x, double y) {
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 &a = m.positions[t.x], &b = m.positions[t.y], &c = m.positions[t.z];
    if (a.z <= 0 || b.z <= 0 || c.z <= 0) continue;
    auto side = [&](const glm::dvec3& p, const glm::dvec3& q) {
      return (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
    };
    if (side(a, b) >= 0 && side(b, c) >= 0 && side(c, a) >= 0) return true;
  }
  return false;
}

TEST(TextMesh, WordIsClosedOutwardAndSizedByTheFont) {
  TextMeshOptions o;
  o.size = 2.0;
  o.depth = 0.3;
  const TriMesh m = make_text_mesh("CGGC", o);
  ASSERT_FALSE(m.empty());
  ASSERT_EQ(m.normals.size(), m.positions.size());
  const Stats s = stats_of(m);
  EXPECT_EQ(s.unpaired, 0) << "every edge shared by exactly two triangles, in opposite directions";
  EXPECT_GT(s.volume, 0.0) << "faces wound outward";
  EXPECT_NEAR(s.box.lo.z, -0.15, 1e-12);
  EXPECT_NEAR(s.box.hi.z, 0.15, 1e-12);
  EXPECT_NEAR(s.box.lo.x + s.box.hi.x, 0.0, 1e-9) << "centred in x";
  EXPECT_NEAR(s.box.lo.y + s.box.hi.y, 0.0, 1e-9) << "centred in y";
  // DejaVu Sans Bold's C and G stand about 0.75 em (with overshoot); four of them are 2.5-3.5 em long.
  EXPECT_NEAR(s.box.hi.y - s.box.lo.y, 0.76 * o.size, 0.05 * o.size);
  EXPECT_GT(s.box.hi.x - s.box.lo.x, 2.5 * o.size);
  EXPECT_LT(s.box.hi.x - s.box.lo.x, 3.5 * o.size);
  for (const glm::dvec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0, 1e-12);
}

TEST(TextMesh, HoleOfAnOStaysOpenAndTheVolumeIsFaceAreaTimesDepth) {
  TextMeshOptions o;
  o.depth = 0.5;
  const TriMesh m = make_text_mesh("O", o);
  const Stats s = stats_of(m);
  EXPECT_EQ(s.unpaired, 0);
  EXPECT_FALSE(front_covers(m, 0.0, 0.0)) << "the counter of the O";
  EXPECT_TRUE(front_covers(m, s.box.lo.x + 0.02, 0.0)) << "its stroke";
  double front_area = 0.0;
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 &a = m.positions[t.x], &b = m.positions[t.y], &c = m.positions[t.z];
    if (a.z > 0 && b.z > 0 && c.z > 0) front_area += 0.5 * glm::cross(b - a, c - a).z;
  }
  EXPECT_GT(front_area, 0.0);
  EXPECT_NEAR(s.volume, front_area * o.depth, 1e-9 * std::abs(s.volume));
}

TEST(TextMesh, SpacesAdvanceAndTheResultIsDeterministic) {
  const TriMesh a = make_text_mesh("I I"), b = make_text_mesh("I I"), one = make_text_mesh("I");
  ASSERT_EQ(a.positions.size(), 2 * one.positions.size());
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
  const Stats s = stats_of(a);
  EXPECT_GT(s.box.hi.x - s.box.lo.x, 0.5) << "a space's advance between the two bars";
}

TEST(TextMesh, RefusesBadTextAndBadFontsNamingWhy) {
  auto message = [](const std::string& text, const TextMeshOptions& o = {}) -> std::string {
    try {
      make_text_mesh(text, o);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message("").find("empty"), std::string::npos);
  EXPECT_NE(message("   ").find("no visible"), std::string::npos);
  EXPECT_NE(message("a\xff").find("UTF-8"), std::string::npos);
  EXPECT_NE(message("\xc0\xaf").find("UTF-8"), std::string::npos) << "overlong";
  EXPECT_NE(message("two\nlines").find("control"), std::string::npos);
  EXPECT_NE(message(std::string(300, 'x')).find("at most 256"), std::string::npos);
  EXPECT_NE(message("\xf4\x8f\xbf\xbd").find("no glyph for U+10FFFD"), std::string::npos);
  TextMeshOptions o;
  o.size = std::nan("");
  EXPECT_NE(message("x", o).find("size"), std::string::npos);
  o = {};
  o.curve_segments = 0;
  EXPECT_NE(message("x", o).find("curve_segments"), std::string::npos);
  o = {};
  o.font_path = "/nonexistent/font.ttf";
  EXPECT_NE(message("x", o).find("no such file"), std::string::npos);
  const std::filesystem::path junk = std::filesystem::temp_directory_path() / "trispline_not_a_font.ttf";
  std::ofstream(junk) << "this is not a font";
  o.font_path = junk.string();
  const std::string junk_error = message("x", o);
  EXPECT_NE(junk_error.find(junk.string()), std::string::npos) << junk_error;
  EXPECT_EQ(junk_error.find("no error"), std::string::npos);
  std::filesystem::remove(junk);
}

}  // namespace
