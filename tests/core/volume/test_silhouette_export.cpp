// Silhouette exports (core/volume/silhouette_export.h): the SVG line drawing parsed back (paths, coordinates within
// the viewBox, projection, hidden runs dashed or absent, the seed's stroke styles) and glTF line strips read back by
// tinygltf.
#include <gtest/gtest.h>

// As core/mesh/gltf_io.cpp: Debian's tinygltf header with no configuration macros.
#include <tiny_gltf.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/mesh/gltf_io.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/uv_sphere.h"
#include "core/volume/silhouette_export.h"

namespace trispline::core {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("trispline_test_silhouette_export_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// One <path> of the SVG: its attributes and its subpaths' points (pixels).
struct SvgPath {
  std::string cls, stroke, dash, gradient, fill;
  double width = 0.0;
  std::vector<std::vector<glm::dvec2>> subpaths;
};

struct Svg {
  int width = 0, height = 0;
  std::string view_box;
  bool white_background = false;
  std::vector<SvgPath> paths;
};

std::string attribute(const std::string& tag, const std::string& name) {
  const std::regex re("\\s" + name + "=\"([^\"]*)\"");
  std::smatch m;
  return std::regex_search(tag, m, re) ? m[1].str() : std::string();
}

Svg parse_svg(const std::string& text) {
  Svg svg;
  std::smatch m;
  EXPECT_TRUE(std::regex_search(text, m, std::regex("<svg[^>]*>")));
  const std::string head = m.str();
  svg.width = std::stoi(attribute(head, "width"));
  svg.height = std::stoi(attribute(head, "height"));
  svg.view_box = attribute(head, "viewBox");
  svg.white_background = std::regex_search(text, std::regex("<rect[^>]*fill=\"#ffffff\""));
  const std::regex path_re("<path[^>]*/>");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), path_re); it != std::sregex_iterator(); ++it) {
    const std::string tag = it->str();
    SvgPath p;
    p.cls = attribute(tag, "class");
    p.stroke = attribute(tag, "stroke");
    p.dash = attribute(tag, "stroke-dasharray");
    p.gradient = attribute(tag, "data-gradient");
    const std::string width = attribute(tag, "stroke-width");
    p.width = width.empty() ? 0.0 : std::stod(width);
    p.fill = attribute(tag, "fill");
    std::istringstream d(attribute(tag, "d"));
    std::string tok;
    std::vector<double> nums;
    auto flush = [&] {
      EXPECT_EQ(nums.size() % 2, 0u);
      if (nums.empty()) return;
      auto& sp = p.subpaths.emplace_back();
      for (std::size_t i = 0; i + 1 < nums.size(); i += 2) sp.push_back({nums[i], nums[i + 1]});
      nums.clear();
    };
    while (d >> tok) {
      if (tok[0] == 'M') {
        flush();
        tok = tok.substr(1);
        if (tok.empty()) continue;
      }
      nums.push_back(std::stod(tok));
    }
    flush();
    svg.paths.push_back(p);
  }
  return svg;
}

// A circle of radius 10 mm about `centre` in the plane z = centre.z; |∇D| rises from 1 to 3 around it; the points
// with y < centre.y are hidden.
SilhouettePolyline circle(const glm::dvec3& centre, int n = 120) {
  SilhouettePolyline pl;
  pl.closed = true;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n;
    pl.points.push_back(centre + 10.0 * glm::dvec3(std::cos(a), std::sin(a), 0.0));
    pl.gradient_norm.push_back(static_cast<float>(1.0 + 2.0 * i / (n - 1)));
    pl.visible.push_back(std::sin(a) >= 0.0 ? 1 : 0);
  }
  return pl;
}

const glm::ivec2 kViewport(400, 300);

glm::dmat4 view_projection() {
  const glm::dmat4 proj = glm::perspective(glm::radians(45.0), 400.0 / 300.0, 1.0, 500.0);
  const glm::dmat4 view = glm::lookAt(glm::dvec3(0, 0, 60), glm::dvec3(0), glm::dvec3(0, 1, 0));
  return proj * view;
}

glm::dvec2 to_pixel(const glm::dvec3& p) {
  const glm::dvec4 c = view_projection() * glm::dvec4(p, 1.0);
  return {(c.x / c.w * 0.5 + 0.5) * kViewport.x, (0.5 - c.y / c.w * 0.5) * kViewport.y};
}

void expect_inside_view_box(const Svg& svg) {
  for (const SvgPath& p : svg.paths)
    for (const auto& sp : p.subpaths)
      for (const glm::dvec2& q : sp) {
        EXPECT_GE(q.x, 0.0);
        EXPECT_LE(q.x, svg.width);
        EXPECT_GE(q.y, 0.0);
        EXPECT_LE(q.y, svg.height);
      }
}

TEST(SilhouetteSvg, PlainStrokeFollowsTheProjectedPoints) {
  TempDir dir;
  SilhouettePolyline pl = circle(glm::dvec3(0.0));
  std::fill(pl.visible.begin(), pl.visible.end(), 1);
  SvgStyle style;
  style.stroke = "plain";
  const fs::path file = dir.path / "plain.svg";
  write_silhouettes_svg(file, {pl}, view_projection(), kViewport, style);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  const Svg svg = parse_svg(read_text(file));
  EXPECT_EQ(svg.width, 400);
  EXPECT_EQ(svg.height, 300);
  EXPECT_EQ(svg.view_box, "0 0 400 300");
  EXPECT_TRUE(svg.white_background);
  ASSERT_EQ(svg.paths.size(), 1u);
  EXPECT_EQ(svg.paths[0].stroke, "#000000");
  EXPECT_TRUE(svg.paths[0].dash.empty());
  ASSERT_EQ(svg.paths[0].subpaths.size(), 1u);
  const auto& pts = svg.paths[0].subpaths[0];
  ASSERT_EQ(pts.size(), pl.points.size() + 1);  // closed: back to the first point
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const glm::dvec2 want = to_pixel(pl.points[i % pl.points.size()]);
    EXPECT_NEAR(pts[i].x, want.x, 0.006);
    EXPECT_NEAR(pts[i].y, want.y, 0.006);
  }
  // (10, 0, 0) lies right of the centre by 10 / (60·tan 22.5°) of the half-height (150 px).
  EXPECT_NEAR(pts[0].x, 200.0 + 10.0 / (60.0 * std::tan(glm::radians(22.5))) * 150.0, 0.01);
  EXPECT_NEAR(pts[0].y, 150.0, 0.01);
}

TEST(SilhouetteSvg, GlyphsAreOneShortStrokePerVisiblePoint) {
  TempDir dir;
  SilhouettePolyline pl = circle(glm::dvec3(0.0));
  std::fill(pl.visible.begin(), pl.visible.end(), 1);
  pl.visible[3] = 0;
  SvgStyle style;
  style.stroke = "glyphs";
  style.hidden = "remove";
  const fs::path file = dir.path / "glyphs.svg";
  write_silhouettes_svg(file, {pl}, view_projection(), kViewport, style);
  const Svg svg = parse_svg(read_text(file));
  std::size_t strokes = 0;
  for (const auto& path : svg.paths) {
    EXPECT_EQ(path.stroke, "#000000");
    for (const auto& sub : path.subpaths) {
      ASSERT_EQ(sub.size(), 2u);
      ++strokes;
    }
  }
  EXPECT_EQ(strokes, pl.points.size() - 1);  // every visible point, none for the hidden one
}

// fans (seed Fig. 7.11): filled sectors with the apex on a visible point, wide and red where |∇D| is low, narrow and
// blue where it is high, at least 1.4 radii apart; none on the hidden point.
TEST(SilhouetteSvg, FansOpenWideWhereTheGradientIsLowAndNarrowWhereItIsHigh) {
  TempDir dir;
  SilhouettePolyline pl = circle(glm::dvec3(0.0), 24);
  std::fill(pl.visible.begin(), pl.visible.end(), 1);
  SvgStyle style;
  style.stroke = "fans";
  style.hidden = "remove";
  const fs::path file = dir.path / "fans.svg";
  write_silhouettes_svg(file, {pl}, view_projection(), kViewport, style);
  const Svg svg = parse_svg(read_text(file));
  struct Fan {
    double opening_deg;
    std::string fill;
  };
  std::vector<Fan> fans;
  for (const auto& path : svg.paths) {
    if (path.cls != "fan") continue;
    EXPECT_EQ(path.stroke, "none");
    for (const auto& sub : path.subpaths) {
      ASSERT_EQ(sub.size(), 8u) << "apex and seven rim points";
      const glm::dvec2 a = sub[1] - sub[0], b = sub[7] - sub[0];
      EXPECT_NEAR(glm::length(a), 6.0, 0.02);
      fans.push_back({glm::degrees(std::acos(glm::dot(a, b) / (glm::length(a) * glm::length(b)))), path.fill});
      for (const glm::dvec2& q : sub) EXPECT_TRUE(q.x >= 0.0 && q.y >= 0.0 && q.x <= 400.0 && q.y <= 300.0);
    }
  }
  ASSERT_GE(fans.size(), 8u);
  // Subpaths come bin by bin (|∇D| grows round the circle): the first fan is the widest and red, the last the
  // narrowest and blue.
  EXPECT_NEAR(fans.front().opening_deg, 150.0, 12.0);
  EXPECT_NEAR(fans.back().opening_deg, 20.0, 12.0);
  EXPECT_EQ(fans.front().fill.substr(0, 3), "#e6");  // hsv(≈0°, 1, 0.9): red
  EXPECT_EQ(fans.back().fill.substr(5, 2), "e6");    // hsv(≈240°, 1, 0.9): blue
}

// chromadepth: bins by depth (data-depth), red where the curve is nearest the eye, blue where it is farthest.
TEST(SilhouetteSvg, ChromaDepthBinsByDepthRedNearBlueFar) {
  TempDir dir;
  SilhouettePolyline pl = circle(glm::dvec3(0.0));
  std::fill(pl.visible.begin(), pl.visible.end(), 1);
  for (glm::dvec3& p : pl.points) p.z = 2.0 * p.x;  // +x nearer the eye (at z = 60)
  SvgStyle style;
  style.stroke = "chromadepth";
  style.bins = 8;
  const fs::path file = dir.path / "chromadepth.svg";
  write_silhouettes_svg(file, {pl}, view_projection(), kViewport, style);
  const std::string text = read_text(file);
  EXPECT_NE(text.find("data-depth="), std::string::npos);
  EXPECT_EQ(text.find("data-gradient="), std::string::npos);
  const Svg svg = parse_svg(text);
  ASSERT_EQ(svg.paths.size(), 8u);
  // The nearest bin's path holds the +x end and is red; the farthest holds the −x end and is blue.
  auto holds = [&](const SvgPath& path, const glm::dvec3& p) {
    const glm::dvec2 want = to_pixel(p);
    for (const auto& sub : path.subpaths)
      for (const glm::dvec2& q : sub)
        if (glm::length(q - want) < 0.5) return true;
    return false;
  };
  const SvgPath* nearest = nullptr;
  const SvgPath* farthest = nullptr;
  for (const SvgPath& path : svg.paths) {
    if (holds(path, pl.points[0])) nearest = &path;    // (10, 0, 20)
    if (holds(path, pl.points[60])) farthest = &path;  // (−10, 0, −20)
  }
  ASSERT_NE(nearest, nullptr);
  ASSERT_NE(farthest, nullptr);
  // The bins' centres: hue 15° (#e63900) nearest, 225° (#0039e6) farthest.
  EXPECT_EQ(nearest->stroke.substr(1, 2), "e6") << nearest->stroke;
  EXPECT_EQ(nearest->stroke.substr(5, 2), "00") << nearest->stroke;
  EXPECT_EQ(farthest->stroke.substr(1, 2), "00") << farthest->stroke;
  EXPECT_EQ(farthest->stroke.substr(5, 2), "e6") << farthest->stroke;
}

TEST(SilhouetteSvg, HiddenRunsDashedOrRemoved) {
  TempDir dir;
  const std::vector<SilhouettePolyline> lines{circle(glm::dvec3(0.0)), circle(glm::dvec3(-5.0, 3.0, -4.0))};
  SvgStyle style;
  style.stroke = "plain";
  write_silhouettes_svg(dir.path / "dashed.svg", lines, view_projection(), kViewport, style);
  const Svg dashed = parse_svg(read_text(dir.path / "dashed.svg"));
  ASSERT_EQ(dashed.paths.size(), 2u);
  EXPECT_EQ(dashed.paths[0].cls, "hidden");  // drawn first, under the visible runs
  EXPECT_EQ(dashed.paths[0].dash, "4 3");
  EXPECT_EQ(dashed.paths[0].stroke, "#999999");
  EXPECT_EQ(dashed.paths[1].cls, "visible");
  EXPECT_TRUE(dashed.paths[1].dash.empty());
  EXPECT_EQ(dashed.paths[0].subpaths.size(), 2u);  // one hidden run per circle (the lower half)
  EXPECT_EQ(dashed.paths[1].subpaths.size(), 2u);
  // Hidden points are the circles' lower halves (world y < centre): below the centre line in pixels (y down), up to
  // the midpoints where a run hands over (half a 0.52 mm segment: under 2 px here).
  const double centre_y[2] = {to_pixel(glm::dvec3(0.0)).y, to_pixel(glm::dvec3(-5.0, 3.0, -4.0)).y};
  for (int k = 0; k < 2; ++k)
    for (const glm::dvec2& q : dashed.paths[0].subpaths[k]) EXPECT_GE(q.y, centre_y[k] - 2.0);
  for (int k = 0; k < 2; ++k)
    for (const glm::dvec2& q : dashed.paths[1].subpaths[k]) EXPECT_LE(q.y, centre_y[k] + 2.0);
  expect_inside_view_box(dashed);

  style.hidden = "remove";
  write_silhouettes_svg(dir.path / "removed.svg", lines, view_projection(), kViewport, style);
  const std::string removed_text = read_text(dir.path / "removed.svg");
  const Svg removed = parse_svg(removed_text);
  ASSERT_EQ(removed.paths.size(), 1u);
  EXPECT_EQ(removed.paths[0].cls, "visible");
  EXPECT_EQ(removed_text.find("dasharray"), std::string::npos);
  EXPECT_EQ(removed.paths[0].subpaths, dashed.paths[1].subpaths);
}

TEST(SilhouetteSvg, HueStyleColoursByGradientInFewPaths) {
  TempDir dir;
  std::vector<SilhouettePolyline> lines;
  for (int i = 0; i < 40; ++i) lines.push_back(circle(glm::dvec3(-20.0 + i, 0.5 * i - 10.0, -i), 60));
  SvgStyle style;  // hue, 16 bins, the data's own gradient range [1, 3]
  write_silhouettes_svg(dir.path / "hue.svg", lines, view_projection(), kViewport, style);
  const Svg svg = parse_svg(read_text(dir.path / "hue.svg"));
  ASSERT_GE(svg.paths.size(), 10u);
  EXPECT_LE(svg.paths.size(), 17u);  // one per bin + the hidden one, however many polylines
  expect_inside_view_box(svg);
  auto rgb = [](const std::string& hex) {
    return glm::ivec3(std::stoi(hex.substr(1, 2), nullptr, 16), std::stoi(hex.substr(3, 2), nullptr, 16),
                      std::stoi(hex.substr(5, 2), nullptr, 16));
  };
  const SvgPath* low = nullptr;
  const SvgPath* high = nullptr;
  for (const SvgPath& p : svg.paths) {
    if (p.cls != "visible") continue;
    EXPECT_DOUBLE_EQ(p.width, 1.5);
    const double g0 = std::stod(p.gradient.substr(0, p.gradient.find(' ')));
    if (!low || g0 < std::stod(low->gradient)) low = &p;
    if (!high || g0 > std::stod(high->gradient)) high = &p;
  }
  ASSERT_TRUE(low && high);
  EXPECT_EQ(low->gradient.substr(0, 1), "1");  // the ramp starts at the smallest |∇D|
  const glm::ivec3 red = rgb(low->stroke), blue = rgb(high->stroke);
  EXPECT_GT(red.x, red.z);    // low |∇D| red (seed Fig. 7.10)
  EXPECT_GT(blue.z, blue.x);  // high |∇D| blue
}

TEST(SilhouetteSvg, WidthStyleThinAndDarkForHighGradient) {
  TempDir dir;
  SvgStyle style;
  style.stroke = "width";
  style.bins = 4;
  style.gradient_min = 1.0;
  style.gradient_max = 3.0;
  SilhouettePolyline pl = circle(glm::dvec3(0.0));
  std::fill(pl.visible.begin(), pl.visible.end(), 1);
  write_silhouettes_svg(dir.path / "w.svg", {pl}, view_projection(), kViewport, style);
  const Svg svg = parse_svg(read_text(dir.path / "w.svg"));
  std::vector<const SvgPath*> visible;
  for (const SvgPath& p : svg.paths)
    if (p.cls == "visible") visible.push_back(&p);
  ASSERT_EQ(visible.size(), 4u);  // bins in increasing |∇D|
  for (std::size_t i = 1; i < visible.size(); ++i) {
    EXPECT_LT(visible[i]->width, visible[i - 1]->width);
    EXPECT_LT(std::stoi(visible[i]->stroke.substr(1, 2), nullptr, 16),
              std::stoi(visible[i - 1]->stroke.substr(1, 2), nullptr, 16));  // darker grey
  }
  EXPECT_LE(visible.front()->width, 4.0);
  EXPECT_GE(visible.back()->width, 1.5);
}

TEST(SilhouetteSvg, ClipsToTheViewAndDropsWhatIsBehindTheEye) {
  TempDir dir;
  SilhouettePolyline pl;  // a line from behind the eye through the view to far off screen
  for (int i = 0; i <= 100; ++i) {
    pl.points.push_back(glm::dvec3(-200.0 + 4.0 * i, 1.0, 100.0 - 2.0 * i));
    pl.gradient_norm.push_back(1.0f);
    pl.visible.push_back(1);
  }
  SvgStyle style;
  style.stroke = "plain";
  write_silhouettes_svg(dir.path / "clip.svg", {pl}, view_projection(), kViewport, style);
  const Svg svg = parse_svg(read_text(dir.path / "clip.svg"));
  ASSERT_EQ(svg.paths.size(), 1u);
  ASSERT_FALSE(svg.paths[0].subpaths.empty());
  expect_inside_view_box(svg);
  const auto& sp = svg.paths[0].subpaths[0];
  EXPECT_GE(sp.size(), 2u);
  bool touches_border = false;
  for (const glm::dvec2& q : sp)
    touches_border = touches_border || q.x == 0.0 || q.x == 400.0 || q.y == 0.0 || q.y == 300.0;
  EXPECT_TRUE(touches_border);
}

TEST(SilhouetteSvg, RefusesBadInput) {
  TempDir dir;
  const auto vp = view_projection();
  SilhouettePolyline bad = circle(glm::dvec3(0.0));
  bad.visible.pop_back();
  EXPECT_THROW(write_silhouettes_svg(dir.path / "a.svg", {bad}, vp, kViewport), std::invalid_argument);
  SilhouettePolyline nan = circle(glm::dvec3(0.0));
  nan.points[3].y = std::nan("");
  EXPECT_THROW(write_silhouettes_svg(dir.path / "a.svg", {nan}, vp, kViewport), std::invalid_argument);
  const std::vector<SilhouettePolyline> ok{circle(glm::dvec3(0.0))};
  EXPECT_THROW(write_silhouettes_svg(dir.path / "a.svg", ok, vp, glm::ivec2(0, 10)), std::invalid_argument);
  SvgStyle style;
  style.stroke = "glyph";
  EXPECT_THROW(write_silhouettes_svg(dir.path / "a.svg", ok, vp, kViewport, style), std::invalid_argument);
  style = {};
  style.hidden = "grey";
  EXPECT_THROW(write_silhouettes_svg(dir.path / "a.svg", ok, vp, kViewport, style), std::invalid_argument);
  style = {};
  style.dash = "4\"/><script";
  EXPECT_THROW(write_silhouettes_svg(dir.path / "a.svg", ok, vp, kViewport, style), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir.path / "a.svg"));
  EXPECT_THROW(write_silhouettes_svg(dir.path / "missing" / "a.svg", ok, vp, kViewport), std::runtime_error);
}

TEST(SilhouetteLineStrips, SplitAtHiddenPointsAndCloseLoops) {
  const SilhouettePolyline pl = circle(glm::dvec3(0.0), 12);  // points 0…6 visible (sin ≥ 0), 7…11 hidden
  const auto all = silhouette_line_strips({pl}, true);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].size(), 13u);
  EXPECT_EQ(all[0].front(), all[0].back());
  const auto seen = silhouette_line_strips({pl}, false);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].size(), 7u);
  EXPECT_EQ(seen[0].front(), glm::vec3(pl.points[0]));
}

TEST(SilhouetteGlb, LineStripsRoundTripThroughTinyGltf) {
  TempDir dir;
  const std::vector<SilhouettePolyline> lines{circle(glm::dvec3(0.0), 30), circle(glm::dvec3(5.0, 2.0, 1.0), 18)};
  const auto strips = silhouette_line_strips(lines, true);
  const TriMesh sphere = make_uv_sphere(8.0, 12, 8);
  std::vector<GltfNode> nodes(3);
  nodes[0].name = "skull";
  nodes[0].mesh = &sphere;
  nodes[1].name = "silhouettes";
  nodes[1].line_strips = &strips;
  nodes[1].color = glm::vec3(0.0f);
  nodes[2].name = "outlined";
  nodes[2].mesh = &sphere;
  nodes[2].line_strips = &strips;
  const fs::path file = dir.path / "lines.glb";
  write_glb(file, nodes);

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, file.string())) << err;
  ASSERT_EQ(model.nodes.size(), 3u);
  const tinygltf::Mesh& lines_mesh = model.meshes.at(model.nodes[1].mesh);
  ASSERT_EQ(lines_mesh.primitives.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    const tinygltf::Primitive& prim = lines_mesh.primitives[s];
    EXPECT_EQ(prim.mode, TINYGLTF_MODE_LINE_STRIP);
    EXPECT_LT(prim.indices, 0);
    const tinygltf::Accessor& acc = model.accessors.at(prim.attributes.at("POSITION"));
    EXPECT_EQ(acc.count, strips[s].size());
    EXPECT_EQ(acc.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    ASSERT_EQ(acc.minValues.size(), 3u);
    const tinygltf::BufferView& view = model.bufferViews.at(acc.bufferView);
    const float* data = reinterpret_cast<const float*>(model.buffers[0].data.data() + view.byteOffset + acc.byteOffset);
    for (std::size_t i = 0; i < acc.count; ++i)
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(data[3 * i + c], strips[s][i][c]);
        EXPECT_GE(data[3 * i + c], acc.minValues[c]);
        EXPECT_LE(data[3 * i + c], acc.maxValues[c]);
      }
    const tinygltf::Material& mat = model.materials.at(prim.material);
    EXPECT_EQ(mat.name, "silhouettes");
    EXPECT_EQ(mat.pbrMetallicRoughness.baseColorFactor[0], 0.0);
    EXPECT_TRUE(mat.extensions.count("KHR_materials_unlit"));
  }
  const tinygltf::Mesh& both = model.meshes.at(model.nodes[2].mesh);
  ASSERT_EQ(both.primitives.size(), 3u);
  EXPECT_EQ(both.primitives[0].mode, TINYGLTF_MODE_TRIANGLES);
  EXPECT_EQ(model.materials.at(both.primitives[1].material).name, "outlined.lines");
  EXPECT_NE(std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_materials_unlit"),
            model.extensionsUsed.end());

  // The project's reader keeps the triangles of both mesh nodes.
  const auto objects = read_gltf_objects(file);
  std::size_t triangles = 0;
  for (const auto& o : objects) triangles += o.mesh.triangle_count();
  EXPECT_EQ(triangles, 2 * sphere.triangle_count());
}

TEST(SilhouetteGlb, NodesWithoutLinesAreWrittenAsBefore) {
  TempDir dir;
  const TriMesh sphere = make_uv_sphere(3.0, 10, 6);
  const std::vector<std::vector<glm::vec3>> none;
  const std::vector<std::vector<glm::vec3>> too_short{{glm::vec3(1.0f)}};
  std::vector<GltfNode> plain(2), with_empty(2);
  plain[0].name = with_empty[0].name = "a";
  plain[0].mesh = with_empty[0].mesh = &sphere;
  plain[1].name = with_empty[1].name = "b";
  with_empty[0].line_strips = &none;
  with_empty[1].line_strips = &too_short;
  write_glb(dir.path / "plain.glb", plain);
  write_glb(dir.path / "empty.glb", with_empty);
  EXPECT_EQ(read_text(dir.path / "plain.glb"), read_text(dir.path / "empty.glb"));

  const std::vector<std::vector<glm::vec3>> nan{{glm::vec3(0.0f), glm::vec3(std::nanf(""), 0.0f, 0.0f)}};
  with_empty[1].line_strips = &nan;
  EXPECT_THROW(write_glb(dir.path / "nan.glb", with_empty), MeshIoError);
}

// A scene.glb with a volume's silhouettes beside a mesh reads back as the mesh alone, its normals kept.
TEST(SilhouetteGlb, LineNodesAreLeftOutWhenTheFileIsReadAsMeshes) {
  TempDir dir;
  const TriMesh sphere = make_uv_sphere(3.0, 10, 6);
  const std::vector<std::vector<glm::vec3>> strips{{glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f)}};
  std::vector<GltfNode> nodes(2);
  nodes[0].name = "ball";
  nodes[0].mesh = &sphere;
  nodes[1].name = "ct/silhouettes";
  nodes[1].line_strips = &strips;
  write_glb(dir.path / "scene.glb", nodes);
  const auto objects = read_gltf_objects(dir.path / "scene.glb");
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0].name, "ball");
  EXPECT_EQ(objects[0].mesh.normals.size(), sphere.positions.size());
}

}  // namespace
}  // namespace trispline::core
