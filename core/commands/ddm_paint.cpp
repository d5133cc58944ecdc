// ddm.paint. See ddm_paint.h. Source: seed ch. 5 (non-covering tiles, §5.3.2 / Fig. 5.10; here a brush over layout
// cells).
#include "core/commands/ddm_paint.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <tuple>

#include "core/commands/ddm_layer_spec.h"
#include "core/ddm/ddm_layer.h"
#include "core/params/codecs.h"
#include "core/raycast/ray_caster.h"
#include "core/scene/ddm_follow.h"

namespace trispline::core {
namespace {

constexpr double kMaxBrushRadiusPx = 16384.0;
constexpr double kCullMarginPx = 2.0;         // occluder triangles: projected bbox grown by this much
constexpr double kLimitGapFactor = 2.0;       // limit base: tolerance = this × |S(cell) − mesh point|
constexpr double kOtherBaseTolerance = 0.01;  // other bases: tolerance = this × the object's diagonal

// A cell whose centre passed the projection and facing tests: the ray test decides.
struct Candidate {
  DdmInstance cell;
  glm::dvec3 p;      // centre on the base surface, world units
  double tol = 0.0;  // how far before p the first hit may be, world units
};

double distance_to_polyline(glm::dvec2 q, const std::vector<glm::dvec2>& line) {
  double best = glm::length(q - line.front());
  for (std::size_t i = 1; i < line.size(); ++i) {
    const glm::dvec2 a = line[i - 1], ab = line[i] - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(q - a, ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, glm::length(q - (a + t * ab)));
  }
  return best;
}

// The triangles of `world` whose projection can cover a pixel of [lo, hi] (their projected bounding box overlaps
// it, or a vertex is at or behind the eye), compacted; `kept` maps new triangle → original index.
TriMesh culled(const TriMesh& world, const Camera& camera, glm::dvec2 lo, glm::dvec2 hi, std::vector<int>* kept) {
  std::vector<glm::dvec3> px(world.positions.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, px.size(), 4096), [&](const auto& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) px[v] = camera.project(world.positions[v]);
  });
  TriMesh out;
  std::vector<int> remap(world.positions.size(), -1);
  for (std::size_t f = 0; f < world.triangles.size(); ++f) {
    const glm::uvec3 t = world.triangles[f];
    glm::dvec2 a(1e300), b(-1e300);
    bool behind = false;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3& q = px[t[k]];
      behind = behind || !(q.z > 0.0);
      a = glm::min(a, glm::dvec2(q));
      b = glm::max(b, glm::dvec2(q));
    }
    if (!behind && (b.x < lo.x || b.y < lo.y || a.x > hi.x || a.y > hi.y)) continue;
    glm::uvec3 n;
    for (int k = 0; k < 3; ++k) {
      int& m = remap[t[k]];
      if (m < 0) m = static_cast<int>(out.positions.size()), out.positions.push_back(world.positions[t[k]]);
      n[k] = static_cast<unsigned>(m);
    }
    out.triangles.push_back(n);
    if (kept) kept->push_back(static_cast<int>(f));
  }
  return out;
}

// The point of face f's flat triangle at chart (3f + k)'s parameters (u, v): the chart's corner quad (vertex k, middle
// of edge (k, k+1), centre, middle of edge (k+2, k)) mapped bilinearly, as DdmSubdivBase's charts (ddm_base.h).
glm::dvec3 flat_point(const TriMesh& mesh, int chart, glm::dvec2 uv) {
  const glm::uvec3 t = mesh.triangles[static_cast<std::size_t>(chart / 3)];
  const int k = chart % 3;
  const glm::dvec3 a = mesh.positions[t[k]], b = mesh.positions[t[(k + 1) % 3]], c = mesh.positions[t[(k + 2) % 3]];
  const glm::dvec3 q00 = a, q10 = 0.5 * (a + b), q11 = (a + b + c) / 3.0, q01 = 0.5 * (a + c);
  return (1 - uv.x) * (1 - uv.y) * q00 + uv.x * (1 - uv.y) * q10 + uv.x * uv.y * q11 + (1 - uv.x) * uv.y * q01;
}

bool share_vertex(const glm::uvec3& a, const glm::uvec3& b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j]) return true;
  return false;
}

using CellKey = std::tuple<int, double, double, double, double>;
CellKey key_of(const DdmInstance& c) { return {c.chart, c.origin.x, c.origin.y, c.size.x, c.size.y}; }

}  // namespace

int ddm_paint_tile_index(int cell_index, int row, int tile_count) {
  return tile_count <= 1 ? 0 : (cell_index + row) % tile_count;
}

std::vector<DdmInstance> ddm_paint_cells(const Scene& scene, const SceneObject& object, const DdmLayer& layer,
                                         const Camera& camera, const std::vector<glm::dvec2>& stroke_px,
                                         double radius_px) {
  if (stroke_px.empty() || !(radius_px > 0.0)) return {};
  std::shared_ptr<const DdmBase> base = layer.surface;
  if (!base) {
    if (!layer.maps) throw std::invalid_argument("layer: '" + layer.name + "' has neither a surface nor maps");
    base = std::make_shared<DdmMapsBase>(layer.maps);
  }
  const bool check_valid = ddm_base_is_uv(layer.base) && layer.maps;
  const int charts = base->chart_count();
  if (!layer.chart_counts.empty() && static_cast<int>(layer.chart_counts.size()) != charts)
    throw std::invalid_argument("layer: '" + layer.name + "' has counts for " +
                                std::to_string(layer.chart_counts.size()) + " charts, its base " +
                                std::to_string(charts));
  // Every candidate cell is evaluated on the base and kept with its point (~250 bytes): weighed before any is made.
  std::size_t layout_cells = 0;
  if (layer.chart_counts.empty())
    layout_cells = static_cast<std::size_t>(charts) * ddm_layout_cell_count(layer.layout, layer.counts);
  else
    for (const glm::ivec2& c : layer.chart_counts) layout_cells += ddm_layout_cell_count(layer.layout, c);
  if (layout_cells > kMaxDdmPaintCandidates) {
    const char* field = layer.tile_size ? "tile_size" : "counts";
    throw CommandError("field '" + std::string(field) + "': the layout of layer '" + layer.name + "' has " +
                           std::to_string(layout_cells) + " cells on " + std::to_string(charts) +
                           " charts for the brush to choose from, over the painting budget of " +
                           std::to_string(kMaxDdmPaintCandidates) + " (fewer cells per chart, larger tiles)",
                       field);
  }
  const int tile_count = std::max<int>(1, static_cast<int>(layer.tiles.size()));
  // One chart's layout cells, each with the tile a pattern fill gives it.
  const auto cells_of = [&](glm::ivec2 counts) {
    std::vector<DdmInstance> cells = ddm_layout_cells(layer.layout, counts, 1);
    for (std::size_t i = 0, row = 0; i < cells.size(); ++i) {  // rows: runs of equal origin.y (ddm_layout_cells' order)
      if (i > 0 && cells[i].origin.y != cells[i - 1].origin.y) ++row;
      cells[i].tile = ddm_paint_tile_index(static_cast<int>(i), static_cast<int>(row), tile_count);
    }
    return cells;
  };
  const std::vector<DdmInstance> uniform_cells = cells_of(layer.counts);

  const glm::dmat4 m = object.transform.matrix();
  const TriMesh& rest = *object.rest_mesh;
  // (The occlusion test's own-face exception needs the world mesh's triangles to be the rest mesh's: not on a split.)
  const bool limit_faces = layer.base == DdmBaseKind::limit && charts == 3 * static_cast<int>(rest.triangle_count()) &&
                           object.world_mesh && object.world_mesh->triangle_count() == rest.triangle_count();
  Aabb box;
  if (object.world_mesh)
    for (const glm::dvec3& p : object.world_mesh->positions) box.extend(p);
  const double diag = box.diagonal();

  glm::dvec2 lo(1e300), hi(-1e300);
  for (const glm::dvec2& q : stroke_px) lo = glm::min(lo, q), hi = glm::max(hi, q);
  lo -= radius_px, hi += radius_px;

  // 1. Every layout cell's centre on the base (per chart: deterministic order), object space.
  struct Centre {
    DdmInstance cell;
    DdmSurfacePoint s;
    glm::dvec3 flat{0.0};  // limit base: the flat face's point under the cell centre, object units
  };
  std::vector<std::vector<Centre>> per_chart_centres(static_cast<std::size_t>(charts));
  tbb::parallel_for(tbb::blocked_range<int>(0, charts, 64), [&](const tbb::blocked_range<int>& r) {
    for (int c = r.begin(); c != r.end(); ++c) {
      const std::vector<DdmInstance> own = layer.chart_counts.empty()
                                               ? std::vector<DdmInstance>()
                                               : cells_of(layer.chart_counts[static_cast<std::size_t>(c)]);
      const std::vector<DdmInstance>& cells = layer.chart_counts.empty() ? uniform_cells : own;
      for (std::size_t i = 0; i < cells.size(); ++i) {
        DdmInstance cell = cells[i];
        cell.chart = c;
        if (check_valid && !ddm_uv_cell_kept(layer.base, *layer.maps, cell)) continue;
        const glm::dvec2 uv = cell.origin + 0.5 * cell.size;
        Centre k{cell, base->eval(c, uv.x, uv.y)};
        if (limit_faces) k.flat = flat_point(rest, c, uv);
        per_chart_centres[static_cast<std::size_t>(c)].push_back(k);
      }
    }
  });
  std::vector<Centre> centres;
  for (auto& v : per_chart_centres) centres.insert(centres.end(), v.begin(), v.end());
  if (centres.empty()) return {};
  // World centres and normals: through the transform, or — on an object whose deformation carries its tiles (FFD,
  // DFFD, clip, morph) — through that deformation at time 0 (what world_mesh shows), each centre as a one-vertex tile.
  std::vector<glm::dvec3> world_p(centres.size()), world_n(centres.size());
  {
    DdmLayer probe = layer;
    probe.tiles.assign(1, DdmTile{"centre", TriMesh{}});
    probe.tiles[0].mesh.positions.assign(1, glm::dvec3(0.0));
    probe.instances.resize(centres.size());
    TriMesh points;
    points.positions.resize(centres.size());
    points.normals.resize(centres.size());
    for (std::size_t i = 0; i < centres.size(); ++i) {
      probe.instances[i] = centres[i].cell, probe.instances[i].tile = 0;
      points.positions[i] = centres[i].s.p, points.normals[i] = centres[i].s.n;
    }
    probe.offset_keys.clear(), probe.offset_velocity = glm::dvec2(0.0);
    const DdmLayerDeformation deform(object, probe, 0.0);
    const TriMesh mapped = deform.rigid() ? transformed(points, object.transform) : deform.apply(points);
    world_p = mapped.positions, world_n = mapped.normals;
  }
  // 2. Within the brush, in front of the eye, facing it.
  std::vector<std::vector<Candidate>> per_chart(static_cast<std::size_t>(charts));
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const glm::dvec3 p = world_p[i];
    const glm::dvec3 q = camera.project(p);
    if (!(q.z > 0.0) || q.x < lo.x || q.y < lo.y || q.x > hi.x || q.y > hi.y) continue;
    if (distance_to_polyline(glm::dvec2(q), stroke_px) > radius_px) continue;
    if (!(glm::dot(world_n[i], camera.eye - p) > 0.0)) continue;
    double tol = kOtherBaseTolerance * diag;
    if (limit_faces)
      tol = 1e-6 * diag + kLimitGapFactor * glm::length(p - glm::dvec3(m * glm::dvec4(centres[i].flat, 1.0)));
    per_chart[static_cast<std::size_t>(centres[i].cell.chart)].push_back({centres[i].cell, p, tol});
  }
  std::vector<Candidate> candidates;
  for (auto& v : per_chart) candidates.insert(candidates.end(), v.begin(), v.end());
  if (candidates.empty()) return {};

  // 2. Occlusion: first hits among the visible objects' world meshes, only triangles that can cover the brush.
  RayCaster rays(BuildQuality::interactive);
  int self_geometry = -1;
  std::vector<int> self_triangles;
  for (const SceneObject& o : scene.objects()) {
    if (!o.visible || !o.world_mesh || o.world_mesh->empty()) continue;
    const bool self = o.name == object.name;
    const TriMesh part =
        culled(*o.world_mesh, camera, lo - kCullMarginPx, hi + kCullMarginPx, self ? &self_triangles : nullptr);
    const int g = rays.add_mesh(part);
    if (self) self_geometry = g;
  }
  rays.commit();
  std::vector<char> visible(candidates.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 64), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Candidate& k = candidates[i];
      const double d = glm::length(k.p - camera.eye);
      const auto hit = rays.intersect(camera.eye, k.p - camera.eye, 0.0, d);
      bool ok = !hit || hit->t >= d - k.tol;
      if (!ok && limit_faces && hit->geometry == self_geometry) {
        const int f = self_triangles[static_cast<std::size_t>(hit->triangle)];
        ok = share_vertex(rest.triangles[static_cast<std::size_t>(f)],
                          rest.triangles[static_cast<std::size_t>(k.cell.chart / 3)]);
      }
      visible[i] = ok;
    }
  });
  std::vector<DdmInstance> out;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (visible[i]) out.push_back(candidates[i].cell);
  return out;
}

auto DdmPaintCommand::declare() -> Schema {
  return Schema("ddm.paint", "Paint (or erase) tiles of a layer with a brush stroke in the viewport (DDM, seed ch. 5)")
      .field("object", &P::object, {.required = true, .help = kDdmLayerObjectHelp})
      .field("layer", &P::layer,
             {.required = true,
              .help = "The layer painted on; a new one is made from the fields below (ddm.fill's, all optional)"})
      .check([](const P& p) { check_ddm_layer_name(p.layer); })
      .embed_named(&P::spec, ddm_layer_schema(false), &P::spec_named)
      .field("stroke", &P::stroke,
             {.required = true,
              .unit = "pixels",
              .help = "Viewport points in drawing order, (0,0) top-left; one point is a dab"})
      .check([](const P& p) {
        if (p.stroke.empty()) params::fail("stroke", "needs at least 1 point");
      })
      // A brush is at most as wide as a large viewport: larger radii select nothing more, and keep the maths
      // finite.
      .field("radius_px", &P::radius_px,
             {.required = true,
              .range = ParamRange{0, kMaxBrushRadiusPx, true, false},
              .unit = "pixels",
              .help = "Brush radius: cells whose centre projects this close to the stroke are touched"})
      .field("erase", &P::erase, {.help = "Remove the touched cells instead of adding them"})
      .object("camera", &P::camera, camera_schema(),
              {.help = "The view the stroke was drawn in (camera.set's fields); default: the last camera.set"})
      .label([](const P& p) {
        return std::string(p.erase ? "Erase tiles of " : "Paint tiles on ") + p.object + "/" + p.layer;
      })
      .failure_field("layer");
}

std::optional<SceneObject> DdmPaintCommand::build(const Scene& scene) {
  const auto t0 = std::chrono::steady_clock::now();
  const SceneObject* object = &require_object(scene, p_.object);
  const Camera& camera = stroke_camera(scene, p_.camera);
  std::shared_ptr<const DdmLayer> existing;
  for (const auto& l : object->ddm_layers)
    if (l->name == p_.layer) existing = l;
  if (!existing && p_.erase)
    throw CommandError("field 'layer': '" + p_.object + "' has no tile layer '" + p_.layer + "' to erase from",
                       "layer");
  // A new layer: the spec's tiles and base, no cells yet (ddm.fill's construction).
  const std::shared_ptr<const DdmLayer> held_layer =
      existing ? existing : make_ddm_layer(*object, p_.layer, p_.spec, false);
  const DdmLayer& layer = *held_layer;

  std::vector<DdmInstance> touched;
  try {
    touched = ddm_paint_cells(scene, *object, layer, camera, p_.stroke, p_.radius_px);
  } catch (const std::invalid_argument& e) {
    throw CommandError("field 'layer': " + std::string(e.what()), "layer");
  }
  if (touched.empty()) {
    char r[32];
    std::snprintf(r, sizeof r, "%g", p_.radius_px);
    throw CommandError("field 'stroke': the stroke touches no visible cell of layer '" + p_.layer + "' on '" +
                           p_.object + "' (brush radius " + r + " px)",
                       "stroke");
  }

  std::set<CellKey> held, hit;
  for (const DdmInstance& c : layer.instances) held.insert(key_of(c));
  for (const DdmInstance& c : touched) hit.insert(key_of(c));
  std::vector<DdmInstance> instances;
  std::size_t added = 0, removed = 0;
  if (p_.erase) {
    for (const DdmInstance& c : layer.instances)
      if (hit.count(key_of(c)))
        ++removed;
      else
        instances.push_back(c);
  } else {
    instances = layer.instances;
    for (const DdmInstance& c : touched)
      if (!held.count(key_of(c))) instances.push_back(c), ++added;
  }

  std::shared_ptr<const DdmLayer> result = held_layer;
  if (added + removed > 0) {
    std::size_t vertices = 0;
    for (const DdmInstance& c : instances)
      if (c.tile >= 0 && c.tile < static_cast<int>(layer.tiles.size()))
        vertices += layer.tiles[static_cast<std::size_t>(c.tile)].mesh.vertex_count();
    const std::size_t limit =
        p_.spec.max_vertices ? static_cast<std::size_t>(*p_.spec.max_vertices) : kMaxDdmLayerVertices;
    if (vertices > limit)
      throw CommandError("field 'stroke': the layer would hold " + std::to_string(vertices) +
                             " tile vertices (at most " + std::to_string(limit) +
                             (p_.spec.max_vertices ? ", max_vertices)" : ")"),
                         "stroke");
    try {
      result = ddm_layer_with_instances(layer, std::move(instances));
    } catch (const std::invalid_argument& e) {
      throw CommandError("field 'layer': " + std::string(e.what()), "layer");
    }
  }
  const DdmLayer& now = *result;
  stats_ = {{"created", !existing},
            {"base", ddm_base_name(now.base)},
            {"touched", touched.size()},
            {"cells_added", added},
            {"cells_removed", removed},
            {"tiles", now.instances.size()},
            {"vertices", now.mesh ? now.mesh->vertex_count() : 0},
            {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return with_ddm_layer(*object, result);
}

}  // namespace trispline::core
