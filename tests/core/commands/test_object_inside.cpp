// object.inside (core/commands/object_inside.h): the colour and texture of an object's cut surfaces. A sphere split
// around a cylinder (dffd.split, capped) gets a PNG texture: its caps get vertices of their own with planar uvs at the
// cut vertices' points, stats say so, undo gives back the untextured mesh bit for bit; a file that is not an image, a
// missing file and contradictory fields fail naming the field, the scene untouched.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "core/commands/dffd_split.h"
#include "core/commands/object_inside.h"
#include "core/commands/scene_primitive.h"
#include "core/mesh/material_image.h"

namespace trispline::core {
namespace object_inside_test {

using nlohmann::json;

struct TempDir {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("trispline_inside_" + std::to_string(::getpid()));
  TempDir() { std::filesystem::create_directories(path); }
  ~TempDir() { std::filesystem::remove_all(path); }
};

// A 32 × 32 two-colour checker written as a real PNG (OpenImageIO).
std::filesystem::path write_checker(const std::filesystem::path& dir) {
  std::vector<std::uint8_t> rgba(32 * 32 * 4);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const bool dark = ((x / 8) + (y / 8)) % 2;
      std::uint8_t* p = &rgba[(y * 32 + x) * 4];
      p[0] = dark ? 90 : 200, p[1] = dark ? 50 : 150, p[2] = dark ? 20 : 90, p[3] = 255;
    }
  const std::vector<std::uint8_t> png = encode_png_rgba8(32, 32, rgba);
  const std::filesystem::path file = dir / "wood.png";
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  return file;
}

Scene split_ball() {
  Scene s;
  CommandContext ctx;
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"sphere","name":"ball"})"), ctx)->redo(s);
  ScenePrimitiveCommand::parse(json::parse(R"({"cmd":"scene.primitive","kind":"cylinder","name":"tool",
      "scale":[0.3,1.6,0.3],"translate":[0.013,0,0.017]})"),
                               ctx)
      ->redo(s);
  DffdSplitCommand::parse(json::parse(R"({"cmd":"dffd.split","object":"ball","obstacles":["tool"],"axis":"x",
      "w_axis":"y","order":[3,3,3],"controls":[16,12,12],"kernel":"gaussian","kernel_width":0.7,"openings":"cap"})"),
                          ctx)
      ->redo(s);
  return s;
}

CommandPtr parse(const std::filesystem::path& dir, const std::string& line) {
  CommandContext ctx;
  ctx.base_dir = dir;
  return ObjectInsideCommand::parse(json::parse(line), ctx);
}

TEST(ObjectInside, TexturedCapsGetVerticesOfTheirOwnAndUndo) {
  TempDir tmp;
  write_checker(tmp.path);
  Scene s = split_ball();
  const SceneObject before = *s.find("ball");
  auto c = parse(tmp.path, R"({"cmd":"object.inside","object":"ball","color":[0.9,0.8,0.7],"texture":"wood.png",
      "texture_size":0.5})");
  c->redo(s);
  const SceneObject& ball = *s.find("ball");
  ASSERT_TRUE(ball.inside_texture);
  EXPECT_EQ(ball.inside_texture->width, 32);
  EXPECT_TRUE(ball.inside_textured());
  EXPECT_EQ(ball.inside_color, glm::vec3(0.9f, 0.8f, 0.7f));
  EXPECT_EQ(ball.inside_texture_size, 0.5);
  EXPECT_EQ(c->stats().at("textured"), true);
  // Same surface, caps on vertices of their own (refined inside): the caps' loop sits exactly on surface points.
  const TriMesh& m = *ball.world_mesh;
  const TriMesh& old = *before.world_mesh;
  ASSERT_GT(m.vertex_count(), old.vertex_count());
  EXPECT_GT(m.triangle_count(), old.triangle_count());
  ASSERT_EQ(m.uvs.size(), m.vertex_count());
  std::set<std::tuple<double, double, double>> surface_points;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> cap_edges;
  std::set<std::uint32_t> cap_vertices;
  for (std::size_t f = 0; f < m.triangle_count(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = m.triangles[f][k], w = m.triangles[f][(k + 1) % 3];
      const glm::dvec3 p = m.positions[v];
      if (m.material(f) != kMaterialInside) {
        surface_points.insert({p.x, p.y, p.z});
      } else {
        cap_vertices.insert(v);
        ++cap_edges[{std::min(v, w), std::max(v, w)}];
      }
    }
  ASSERT_FALSE(cap_vertices.empty());
  for (const auto& [e, n] : cap_edges)
    if (n == 1)
      for (const std::uint32_t v : {e.first, e.second}) {
        const glm::dvec3 p = m.positions[v];
        EXPECT_TRUE(surface_points.count({p.x, p.y, p.z})) << v;
      }
  glm::dvec2 lo(1e9), hi(-1e9);
  for (std::uint32_t v : cap_vertices) lo = glm::min(lo, m.uvs[v]), hi = glm::max(hi, m.uvs[v]);
  // The sphere (radius 1) is cut by the x plane: the caps span about its height and depth, 2 units = 4 repeats.
  EXPECT_GT(hi.x - lo.x, 2.5);
  EXPECT_LT(hi.x - lo.x, 4.5);
  // The log line round-trips.
  EXPECT_EQ(parse(tmp.path, c->to_json().dump())->to_json(), c->to_json());
  // Undo: the untextured object, its mesh bit for bit.
  c->undo(s);
  EXPECT_FALSE(s.find("ball")->inside_texture);
  EXPECT_EQ(s.find("ball")->world_mesh->positions, old.positions);
  EXPECT_EQ(s.find("ball")->world_mesh->triangles, old.triangles);
  // Removing the texture again gives the untextured caps.
  c->redo(s);
  parse(tmp.path, R"({"cmd":"object.inside","object":"ball","no_texture":true})")->redo(s);
  EXPECT_EQ(s.find("ball")->world_mesh->triangles, old.triangles);
  EXPECT_EQ(s.find("ball")->world_mesh->positions, old.positions);
}

TEST(ObjectInside, BadInputNamesTheFieldAndChangesNothing) {
  TempDir tmp;
  std::ofstream(tmp.path / "not_an_image.png") << "this is text, not a PNG";
  Scene s = split_ball();
  const std::shared_ptr<const TriMesh> mesh = s.find("ball")->world_mesh;
  auto field_of = [&](const std::string& line) -> std::string {
    try {
      parse(tmp.path, line)->redo(s);
    } catch (const CommandError& e) {
      return e.field();
    }
    return "(no error)";
  };
  EXPECT_EQ(field_of(R"({"cmd":"object.inside","object":"ball","texture":"not_an_image.png"})"), "texture");
  EXPECT_EQ(field_of(R"({"cmd":"object.inside","object":"ball","texture":"missing.png"})"), "texture");
  EXPECT_EQ(field_of(R"({"cmd":"object.inside","object":"ball","texture":"x.png","no_texture":true})"), "no_texture");
  EXPECT_EQ(field_of(R"({"cmd":"object.inside","object":"ball"})"), "color");
  EXPECT_EQ(field_of(R"({"cmd":"object.inside","object":"ball","texture_size":0})"), "texture_size");
  EXPECT_EQ(field_of(R"({"cmd":"object.inside","object":"ball","color":[2,0,0]})"), "color");
  EXPECT_EQ(field_of(R"({"cmd":"object.inside","object":"nobody","color":[1,0,0]})"), "object");
  EXPECT_EQ(s.find("ball")->world_mesh, mesh);
  EXPECT_FALSE(s.find("ball")->inside_texture);
}

}  // namespace object_inside_test
}  // namespace trispline::core
