// Live DDM layers on the GPU (gpu/eval/ddm_gl.h, shaders/ddm.vert.glsl, seed §5.3.2) against the CPU
// reference core::ddm_layer_mesh (ddm_evaluate over DdmMapsBase), for real on llvmpipe: every base kind (the
// teapot's body patches as one periodic chart, the Loop limit surface of a polygonal sphere, a UV-mapped terrain),
// with a tile-space transform (fixed and keyed over time), a texture-space offset (wrapping on the periodic chart,
// clamped elsewhere), several tiles in one layer and the thorn → flower metamorphosis at α = 0.3. Tolerances (the DDM
// bars): positions ≤ 1e-5 × maps.base_size, normals ≤ 1e-4. Then the renderer: a layer is drawn (pixels change) and
// counted in RenderStats.
#include <cstdio>
#include <filesystem>

#include "core/ddm/ddm_layer.h"
#include "core/ddm/ddm_pn_maps.h"
#include "core/mesh/mesh_io.h"
#include "core/scene/primitives.h"
#include "gl_test.h"
#include "gpu/eval/ddm_gl.h"
#include "tests/ddm_follow_cases.h"

namespace trispline::gpu::test {
namespace {

constexpr double kPosTol = 1e-5;  // × maps.base_size
constexpr double kNrmTol = 1e-4;  // |n_gpu − n_cpu|, unit vectors

std::shared_ptr<core::DdmLayer> make_layer(const std::string& name, std::vector<core::DdmTile> tiles,
                                           std::vector<core::DdmInstance> instances, core::DdmMaps maps,
                                           double height) {
  auto layer = std::make_shared<core::DdmLayer>();
  layer->name = name;
  layer->tiles = std::move(tiles);
  layer->instances = std::move(instances);
  layer->maps = std::make_shared<const core::DdmMaps>(std::move(maps));
  layer->height = height;
  return layer;
}

std::vector<int> all_charts(int n) {
  std::vector<int> c(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) c[static_cast<std::size_t>(i)] = i;
  return c;
}

// GPU capture at `time_s` against ddm_layer_mesh; returns the vertex count compared.
std::size_t expect_parity(DdmGl& gl, const std::shared_ptr<const core::DdmLayer>& layer, double time_s,
                          const char* what) {
  const core::TriMesh ref = core::ddm_layer_mesh(*layer, time_s);
  const DdmCapture gpu = gl.capture(layer, DdmPose::at(*layer, time_s));
  EXPECT_EQ(gpu.positions.size(), ref.vertex_count()) << what;
  EXPECT_EQ(gpu.normals.size(), ref.vertex_count()) << what;
  if (gpu.positions.size() != ref.vertex_count() || gpu.normals.size() != ref.vertex_count()) return 0;
  double worst_p = 0.0, worst_n = 0.0;
  std::size_t worst_at = 0;
  for (std::size_t i = 0; i < ref.vertex_count(); ++i) {
    const double dp = glm::length(glm::dvec3(gpu.positions[i]) - ref.positions[i]);
    if (!(dp <= worst_p)) worst_p = dp, worst_at = i;  // NaN counts as worst
    const double dn = glm::length(glm::dvec3(gpu.normals[i]) - ref.normals[i]);
    if (!(dn <= worst_n)) worst_n = dn;
  }
  const double size = layer->maps->base_size;
  std::printf("[ddm parity] %-34s %8zu vertices: max |Δp| = %.3g (%.3g × base size %.3g), max |Δn| = %.3g\n", what,
              ref.vertex_count(), worst_p, worst_p / size, size, worst_n);
  EXPECT_LE(worst_p, kPosTol * size) << what << ": worst vertex " << worst_at;
  EXPECT_LE(worst_n, kNrmTol) << what;
  return ref.vertex_count();
}

class DdmGlTest : public GlTest {};

// The teapot's body: 8 Bézier patches as one chart, periodic around (u); two tiles alternating, a tile transform,
// an offset that wraps around the pot, and the metamorphosis thorn → flower (hex → hex) at α = 0.3.
TEST_F(DdmGlTest, SplineBaseMatchesTheCpuReference) {
  const core::DdmSplineBase base(core::teapot_body_patches(), {4, 2}, {true, false});
  core::DdmMaps maps = core::ddm_sample_maps(base, {0}, {65, 33});
  ASSERT_TRUE(maps.periodic.x);
  std::vector<core::DdmInstance> cells = core::ddm_layout_cells(core::DdmLayout::rect, {12, 5}, 1);
  for (std::size_t k = 0; k < cells.size(); ++k) cells[k].tile = int(k % 3 == 1);  // tiles interleaved
  auto layer =
      make_layer("thorns", {core::make_ddm_tile("thorn"), core::make_ddm_tile("hex")}, cells, std::move(maps), 0.06);
  DdmGl gl;
  expect_parity(gl, layer, 0.0, "teapot body, two tiles");

  auto moved = std::make_shared<core::DdmLayer>(*layer);
  moved->transform.scale = {0.8, 1.1};
  moved->transform.rotate_deg = 23.0;
  moved->transform.shift = {0.07, -0.04};
  moved->offset_velocity = {0.41, 0.0};  // 0.41 · 2.5 s = 1.025 turns: wraps around the periodic chart
  expect_parity(gl, moved, 2.5, "teapot body, transform + offset");

  auto keyed = std::make_shared<core::DdmLayer>(*moved);  // rotation, scale and w keyed (seed §5.4.2)
  keyed->rotate_keys = {{0.0, glm::dvec3(0.0)}, {4.0, glm::dvec3(400.0, 0.0, 0.0)}};
  keyed->scale_keys = {{0.0, glm::dvec3(1.0)}, {4.0, glm::dvec3(0.4, 0.0, 0.0)}};
  keyed->w_keys = {{0.0, glm::dvec3(1.0), core::KeyInterpolation::smooth}, {4.0, glm::dvec3(3.0, 0.0, 0.0)}};
  expect_parity(gl, keyed, 2.5, "teapot body, keyed rotate/scale/w");

  auto morph = std::make_shared<core::DdmLayer>(*moved);
  morph->morph_tiles = {core::make_ddm_tile("flower"), core::make_ddm_tile("hex")};
  morph->alpha = 0.3;
  EXPECT_GT(expect_parity(gl, morph, 2.5, "teapot body, thorn→flower α=0.3"), 0u);
  morph->alpha = 1.6;  // extrapolation is allowed (Eq. 5.3 with α outside [0,1])
  expect_parity(gl, morph, 0.0, "teapot body, α=1.6");
  EXPECT_EQ(gl.cached_layers(), 4u);  // the α = 1.6 draw reused morph's upload (α is a uniform)
}

// An articulated tile (seed Fig. 5.13): Qt 3D's RiggedFigure (assets/data, a skinned glTF whose 19 animations each
// move one joint) standing on the teapot body, all its animations played together. The GPU's per-frame re-posed tile
// buffers match the CPU reference at two times, and the two poses differ.
TEST_F(DdmGlTest, ArticulatedTilesMatchTheCpuReferenceAtEveryTime) {
  const std::filesystem::path path = TRISPLINE_SOURCE_DIR "/assets/data/qt3d/gltf/2.0/RiggedFigure/RiggedFigure.gltf";
  auto clip = std::make_shared<core::DdmTileClip>();
  clip->clip = core::MeshClip::load(path, core::kAllClips);
  clip->up_axis = 1;
  core::TriMesh rest = core::load_mesh(path);
  core::ddm_tile_up(rest, 1);
  clip->frame = core::canonical_ddm_tile_frame(rest, "RiggedFigure");
  const core::DdmSplineBase base(core::teapot_body_patches(), {4, 2}, {true, false});
  core::DdmMaps maps = core::ddm_sample_maps(base, {0}, {65, 33});
  auto layer = make_layer("robots", {core::canonical_ddm_tile(rest, "RiggedFigure")},
                          core::ddm_layout_cells(core::DdmLayout::rect, {10, 3}, 1), std::move(maps), 0.1);
  layer->tile_clip = clip;
  ASSERT_TRUE(layer->animated());
  DdmGl gl;
  EXPECT_GT(expect_parity(gl, layer, 0.3, "teapot body, walking figures t=0.3"), 0u);
  EXPECT_GT(expect_parity(gl, layer, 0.9, "teapot body, walking figures t=0.9"), 0u);
  const core::TriMesh a = core::ddm_layer_mesh(*layer, 0.3), b = core::ddm_layer_mesh(*layer, 0.9);
  double moved = 0.0;
  for (std::size_t v = 0; v < a.vertex_count(); ++v)
    moved = std::max(moved, glm::length(a.positions[v] - b.positions[v]));
  EXPECT_GT(moved, 1e-3) << "the figures move between the two times";
  EXPECT_EQ(gl.cached_layers(), 1u) << "re-posing keeps the layer's upload";
}

// The Loop limit surface of a polygonal sphere: three charts per triangle, one tile per chart, with a transform and a
// (clamped, non-periodic) offset.
TEST_F(DdmGlTest, LimitBaseMatchesTheCpuReference) {
  const core::DdmSubdivBase base(core::make_sphere(8, 4));
  const int charts = base.chart_count();
  ASSERT_GT(charts, 0);
  core::DdmMaps maps = core::ddm_sample_maps(base, all_charts(charts), {9, 9});
  auto layer = make_layer("limit", {core::make_ddm_tile("thorn")},
                          core::ddm_layout_cells(core::DdmLayout::rect, {1, 1}, charts), std::move(maps), 0.15);
  DdmGl gl;
  expect_parity(gl, layer, 0.0, "limit surface");
  auto moved = std::make_shared<core::DdmLayer>(*layer);
  moved->transform.scale = {0.7, 0.7};
  moved->transform.rotate_deg = -35.0;
  moved->offset_velocity = {0.05, -0.08};
  expect_parity(gl, moved, 1.0, "limit surface, transform + offset");
}

// A UV-mapped terrain rasterised into P/N maps in its texture space (seed §5.4.1), hexagonal layout.
TEST_F(DdmGlTest, UvBaseMatchesTheCpuReference) {
  const core::TriMesh terrain = core::make_terrain(7, 24);
  ASSERT_EQ(terrain.uvs.size(), terrain.vertex_count());
  core::DdmMaps maps = core::ddm_rasterize_uv_maps(terrain, 97);
  auto layer = make_layer("uv", {core::make_ddm_tile("hex")}, core::ddm_layout_cells(core::DdmLayout::hex, {7, 6}, 1),
                          std::move(maps), 0.08);
  layer->base = core::DdmBaseKind::uv;
  DdmGl gl;
  expect_parity(gl, layer, 0.0, "uv terrain");
  auto moved = std::make_shared<core::DdmLayer>(*layer);
  moved->transform.scale = {0.9, 0.9};
  moved->transform.rotate_deg = 10.0;
  moved->offset_velocity = {0.03, 0.02};
  expect_parity(gl, moved, 1.5, "uv terrain, transform + offset");
}

TEST_F(DdmGlTest, CachesReleaseAndBadInput) {
  const core::DdmSplineBase base(core::teapot_body_patches(), {4, 2}, {true, false});
  auto layer = make_layer("a", {core::make_ddm_tile("thorn")}, core::ddm_layout_cells(core::DdmLayout::rect, {3, 2}, 1),
                          core::ddm_sample_maps(base, {0}, {17, 9}), 0.05);
  DdmGl gl;
  const DdmCapture a = gl.capture(layer, {});
  const DdmCapture b = gl.capture(layer, {});
  EXPECT_EQ(a.positions, b.positions);  // deterministic
  EXPECT_EQ(gl.uploads(), 2);           // the layer and its maps, once
  EXPECT_EQ(gl.cached_layers(), 1u);
  EXPECT_EQ(gl.cached_maps(), 1u);
  auto second = std::make_shared<core::DdmLayer>(*layer);  // shares the maps
  second->instances.resize(2);
  EXPECT_EQ(gl.capture(second, {}).positions.size(), 2 * layer->tiles[0].mesh.vertex_count());
  EXPECT_EQ(gl.cached_maps(), 1u);
  gl.release_unused({second.get()});
  EXPECT_EQ(gl.cached_layers(), 1u);
  EXPECT_EQ(gl.cached_maps(), 1u);
  gl.release_unused({});
  EXPECT_EQ(gl.cached_layers(), 0u);
  EXPECT_EQ(gl.cached_maps(), 0u);

  auto empty = std::make_shared<core::DdmLayer>(*layer);
  empty->instances.clear();
  EXPECT_TRUE(gl.capture(empty, {}).positions.empty());

  auto unsampled = std::make_shared<core::DdmLayer>(*layer);
  unsampled->instances[1].chart = 1;  // the maps hold chart 0 only
  EXPECT_THROW(gl.capture(unsampled, {}), std::invalid_argument);
  auto no_maps = std::make_shared<core::DdmLayer>(*layer);
  no_maps->maps = nullptr;
  EXPECT_THROW(gl.capture(no_maps, {}), std::invalid_argument);
  auto bad_morph = std::make_shared<core::DdmLayer>(*layer);
  bad_morph->morph_tiles = {core::make_ddm_tile("chain")};
  EXPECT_THROW(gl.capture(bad_morph, {}), std::invalid_argument);
  auto bad_tile = std::make_shared<core::DdmLayer>(*layer);
  bad_tile->instances[0].tile = 3;
  EXPECT_THROW(gl.capture(bad_tile, {}), std::invalid_argument);
  EXPECT_THROW(gl.capture(nullptr, {}), std::invalid_argument);
}

int count_different(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b) {
  int n = 0;
  for (std::size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
    n += std::abs(a[i] - b[i]) + std::abs(a[i + 1] - b[i + 1]) + std::abs(a[i + 2] - b[i + 2]) > 24;
  return n;
}

// A sphere object (moved and scaled by its transform) with thorns on its limit surface: drawn, counted, outlined.
TEST_F(DdmGlTest, RendererDrawsLiveLayersThroughTheObjectTransform) {
  const core::TriMesh sphere = core::make_sphere(8, 4);
  core::SceneObject o = make_object("ball", sphere, {0.8f, 0.1f, 0.1f});
  o.transform.translate = {0.3, -0.1, 0.0};
  o.transform.scale = {0.8, 0.8, 0.8};
  o.refresh();
  const auto base = std::make_shared<const core::DdmSubdivBase>(sphere);
  auto layer = make_layer("thorns", {core::make_ddm_tile("thorn")},
                          core::ddm_layout_cells(core::DdmLayout::rect, {1, 1}, base->chart_count()),
                          core::ddm_sample_maps(*base, all_charts(base->chart_count()), {9, 9}), 0.35);
  layer->surface = base;
  core::Scene plain;
  plain.insert(o);
  core::Scene tiled;
  o.ddm_layers.push_back(layer);
  tiled.insert(o);

  Renderer renderer;
  const core::Camera cam = front_camera(160, 120);
  const std::vector<unsigned char> without = render(renderer, plain, cam);
  EXPECT_EQ(renderer.last_stats().ddm_layers_drawn, 0);
  EXPECT_EQ(renderer.last_stats().ddm_vertices, 0u);
  const std::vector<unsigned char> with = render(renderer, tiled, cam);
  const RenderStats s = renderer.last_stats();
  EXPECT_EQ(s.ddm_layers_drawn, 1);
  EXPECT_EQ(s.ddm_vertices, layer->instances.size() * layer->tiles[0].mesh.vertex_count());
  EXPECT_GE(s.ddm_ms, 0.0);  // wall clock on llvmpipe: available at once
  const int changed = count_different(without, with);
  std::printf("[ddm render] %d of %d pixels changed by %zu tile vertices\n", changed, 160 * 120, s.ddm_vertices);
  EXPECT_GT(changed, 300);
  // Drawn again from the cache: the same image (the layer upload must leave the object's vertex array alone).
  EXPECT_EQ(count_different(with, render(renderer, tiled, cam)), 0);
  EXPECT_EQ(renderer.last_stats().ddm_vertices, s.ddm_vertices);
  // The layer follows the object's transform.
  core::Scene shifted = tiled;
  shifted.find("ball")->transform.translate = {-0.3, -0.1, 0.0};
  shifted.find("ball")->refresh();
  const std::vector<unsigned char> moved = render(renderer, shifted, cam);
  EXPECT_GT(count_different(with, moved), 300);

  ViewOptions opt;
  opt.wireframe = true;
  opt.selected = "ball";
  const std::vector<unsigned char> outlined = render(renderer, tiled, cam, opt);
  EXPECT_EQ(renderer.last_stats().ddm_layers_drawn, 1);
  EXPECT_GT(count_different(with, outlined), 0);

  renderer.release_unused(plain);  // the layer is gone: its GPU copy too (nothing to observe but no GL error)
  const std::vector<unsigned char> again = render(renderer, plain, cam);
  EXPECT_EQ(count_different(without, again), 0);
}

// Texture-mapped tiles (seed Fig. 5.12): thorns whose uvs run along the tile's x over a 2 × 1 texture, red on the left
// and green on the right. Capture is unchanged by the uvs (parity with the CPU reference); Material shading draws the
// texture's red and green where Solid draws the object's blue, and automatic shading picks Material by itself.
TEST_F(DdmGlTest, TextureMappedTilesShowTheirTextureInMaterialShading) {
  const core::TriMesh sphere = core::make_sphere(8, 4);
  core::SceneObject o = make_object("ball", sphere, {0.1f, 0.2f, 0.9f});
  core::TriMesh thorn = core::make_ddm_tile("thorn").mesh;
  thorn.uvs.resize(thorn.vertex_count());
  for (std::size_t v = 0; v < thorn.vertex_count(); ++v) thorn.uvs[v] = {thorn.positions[v].x, 0.5};
  auto set = std::make_shared<core::MaterialSet>();
  auto image = std::make_shared<core::MaterialImage>();
  image->width = 2, image->height = 1;
  image->rgba8 = {255, 0, 0, 255, 0, 255, 0, 255};
  set->images.push_back(image);
  core::Material m;
  m.name = "red_green";
  m.base_color_texture.image = 0;
  m.base_color_texture.sampler.mag_filter = core::TextureFilter::Nearest;
  m.metallic = 0.0;
  set->materials.push_back(m);
  const core::DdmTile tile = core::canonical_ddm_tile(thorn, "painted", set);
  ASSERT_TRUE(tile.materials);
  const auto base = std::make_shared<const core::DdmSubdivBase>(sphere);
  auto layer = make_layer("painted", {tile}, core::ddm_layout_cells(core::DdmLayout::rect, {1, 1}, base->chart_count()),
                          core::ddm_sample_maps(*base, all_charts(base->chart_count()), {9, 9}), 0.35);
  layer->surface = base;
  DdmGl gl;
  expect_parity(gl, layer, 0.0, "texture-mapped thorns");
  EXPECT_EQ(gl.materials(layer, glm::dvec3(1.0)).get(), set.get());
  o.ddm_layers.push_back(layer);
  core::Scene scene;
  scene.insert(o);
  EXPECT_TRUE(material_shading(scene, Shading::automatic)) << "a scene with texture-mapped tiles is a textured scene";

  Renderer renderer;
  const core::Camera cam = front_camera(160, 120);
  ViewOptions solid, material;
  solid.shading = Shading::solid;
  material.shading = Shading::material;
  const std::vector<unsigned char> a = render(renderer, scene, cam, solid), b = render(renderer, scene, cam, material);
  const auto count = [](const std::vector<unsigned char>& px, int channel) {
    int n = 0;  // pixels where `channel` clearly dominates the other two
    for (std::size_t i = 0; i + 3 < px.size(); i += 4) {
      const int c = px[i + std::size_t(channel)], o1 = px[i + std::size_t((channel + 1) % 3)],
                o2 = px[i + std::size_t((channel + 2) % 3)];
      n += c > 2 * o1 + 20 && c > 2 * o2 + 20;
    }
    return n;
  };
  std::printf("[ddm textured] solid: red %d green %d; material: red %d green %d\n", count(a, 0), count(a, 1),
              count(b, 0), count(b, 1));
  EXPECT_LT(count(a, 0) + count(a, 1), 20) << "Solid draws the tiles in the object's blue";
  EXPECT_GT(count(b, 0), 150) << "Material draws the texture's red half";
  EXPECT_GT(count(b, 1), 150) << "Material draws the texture's green half";
}

}  // namespace
}  // namespace trispline::gpu::test

namespace trispline::gpu::test {

// Tiles following their object (core::DdmLayerDeformation, the FOLLOW / FFD variants of ddm.vert.glsl): an FFD with
// a parameter offset, moved host triangles, a DFFD's opened break — captured in world units against the CPU
// reference apply(). Positions ≤ 1e-5 × the object's size (its world box diagonal), normals ≤ 1e-4.
namespace follow {
void expect_follow_parity(DdmGl& gl, const core::SceneObject& o, const char* what) {
  const auto& layer = o.ddm_layers.front();
  const core::DdmLayerDeformation d(o, *layer, 0.0);
  ASSERT_FALSE(d.rigid()) << what;
  std::unique_ptr<FfdLatticeBuffers> lattice;
  if (d.lattice()) {
    lattice = std::make_unique<FfdLatticeBuffers>();
    lattice->upload(core::FfdPackedLattice::build(*d.lattice(), d.embedding()));
  }
  const DdmFollow f{&d, lattice.get()};
  const DdmCapture gpu = gl.capture(layer, DdmPose::at(*layer, 0.0), &f);
  const core::TriMesh ref = d.apply(*layer->mesh);
  ASSERT_EQ(gpu.positions.size(), ref.vertex_count()) << what;
  core::Aabb box;
  for (const glm::dvec3& p : ref.positions) box.extend(p);
  double worst_p = 0.0, worst_n = 0.0;
  for (std::size_t i = 0; i < ref.vertex_count(); ++i) {
    const double dp = glm::length(glm::dvec3(gpu.positions[i]) - ref.positions[i]);
    if (!(dp <= worst_p)) worst_p = dp;
    const double dn = glm::length(glm::dvec3(gpu.normals[i]) - ref.normals[i]);
    if (!(dn <= worst_n)) worst_n = dn;
  }
  std::printf("[ddm follow parity] %-12s %8zu vertices: max |Δp| = %.3g (%.3g × size %.3g), max |Δn| = %.3g\n", what,
              ref.vertex_count(), worst_p, worst_p / box.diagonal(), box.diagonal(), worst_n);
  EXPECT_LE(worst_p, 1e-5 * box.diagonal()) << what;
  EXPECT_LE(worst_n, 1e-4) << what;
}
}  // namespace follow

TEST_F(DdmGlTest, FollowingLayersMatchTheCpuReference) {
  DdmGl gl;
  follow::expect_follow_parity(gl, trispline::test::ffd_case(), "ffd");
  follow::expect_follow_parity(gl, trispline::test::host_case(), "host maps");
  follow::expect_follow_parity(gl, trispline::test::dffd_case(), "dffd");
}

}  // namespace trispline::gpu::test
