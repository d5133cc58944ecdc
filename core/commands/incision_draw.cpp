#include "core/commands/incision_draw.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/params/codecs.h"
#include "core/raycast/ray_caster.h"

namespace trispline::core {

const ParamSchema<IncisionParams>& incision_schema() {
  using I = IncisionParams;
  static const ParamSchema<I> s =
      ParamSchema<I>("incision", "The shape of an incision (seed §6.4, Eq. 6.2)")
          .field("width", &I::width,
                 ParamSchema<I>::object_length("Width", {0.02, 0.0005, 0.5, 0.01},
                                               "α: how far the cut pushes the surface apart to each side (the "
                                               "lattice spans ±width across the cut; Eq. 6.2)",
                                               true))
          .field("depth", &I::depth,
                 ParamSchema<I>::object_length("Depth", {0.02, 0.0005, 0.5, 0.01},
                                               "β: how deep below the surface the cut goes, along −N (Eq. 6.2)", true))
          .field("opening", &I::opening,
                 ParamSchema<I>::object_length("Opening", {0.006, 0.0, 0.2, 0.01},
                                               "Gap between the two cut faces at the surface, mid-stroke; it tapers "
                                               "to 0 at the cut's bottom and at both ends of the stroke (§6.4)",
                                               false, true))
          .field(
              "walls", &I::walls,
              {.ui = {"Walls"},
               .help = "Build cut-depth walls (inside colour) so the surface stays closed; false leaves the cut open"})
          .field(
              "order", &I::order,
              {.range = ParamRange{2, 4},
               .ui = {"Order", 0.05},
               .help = "Order (= degree + 1) of the cutting lattice in u, v, w; order knots at u = 1/2 make the cut"})
          .choice(
              "kernel", &I::kernel, {"gaussian", "bspline"},
              {.ui = {"Kernel"},
               .help =
                   "κ: how the planes next to the cut follow it: truncated Gaussian or quadratic B-spline (§6.3.1)"})
          .field("wall_rows", &I::wall_rows,
                 {.range = ParamRange{1, 32}, .help = "Rows of wall quads from each rim to the bottom"});
  return s;
}

auto IncisionDrawCommand::declare() -> Schema {
  return Schema("incision.draw", "Cut an incision drawn on a surface: width, depth, opening, walls (seed §6.4)")
      .field("object", &P::object, {.required = true, .help = "An undeformed object (no ffd, dffd or clip)"})
      .field(
          "stroke", &P::stroke,
          {.required = true,
           .unit = "pixels",
           .help = "Viewport points of the line's camera (else the scene camera), ≥ 2; each ray hits this object only"})
      .check([](const P& p) {
        if (p.stroke.size() < 2) params::fail("stroke", "needs at least 2 points");
      })
      .object("camera", &P::camera, camera_schema(), {.help = "The view the stroke was drawn in (camera.set's fields)"})
      .embed(&P::incision, incision_schema())
      .field("controls", &P::controls,
             {.default_text = "[7, clamp(#hits/3, order, 24), 5]",
              .help = "[l, m, n] before knot insertion: l, n odd in max(3, order)..31, m in order..64"})
      .check([](const P& p) {
        if (!p.controls) return;
        const glm::ivec3 n = *p.controls;
        const int o = p.incision.order;
        if (n.x % 2 == 0 || n.x < std::max(3, o) || n.x > 31 || n.y < o || n.y > 64 || n.z % 2 == 0 ||
            n.z < std::max(3, o) || n.z > 31)
          params::fail("controls", "[l, m, n] with l, n odd in max(3, order)..31 and m in order..64");
      })
      .label([](const P& p) {
        char buf[96];
        std::snprintf(buf, sizeof buf, " (depth %g, opening %g)", p.incision.depth, p.incision.opening);
        return "Incision on '" + p.object + "'" + buf;
      });
}

namespace {
IncisionParams incision_params(const IncisionDrawParams& p) {
  IncisionParams out = p.incision;
  if (p.controls) out.controls_u = p.controls->x, out.controls_v = p.controls->y, out.controls_w = p.controls->z;
  return out;
}
}  // namespace

std::optional<SceneObject> IncisionDrawCommand::build(const Scene& scene) {
  const SceneObject* object = &require_object(scene, p_.object);
  if (object->morph && object->morph->animated())
    throw CommandError("field 'object': '" + p_.object +
                           "' has an animated incision opening; clear it first "
                           "(incision.animate with \"clear\":true) and cut again",
                       "object");
  if (object->ffd || object->dffd || object->clip)
    throw CommandError("field 'object': '" + p_.object +
                           "' is deformed (FFD, DFFD or clip); incisions cut "
                           "undeformed objects only",
                       "object");
  if (!object->rest_mesh || object->rest_mesh->empty())
    throw CommandError("field 'object': '" + p_.object + "' has no triangles to cut", "object");
  const Camera& camera = stroke_camera(scene, p_.camera);
  const auto t0 = std::chrono::steady_clock::now();
  // world_mesh is T(rest) for an object without ffd / dffd / clip (SceneObject::refresh).
  const TriMesh fallback = object->world_mesh ? TriMesh{} : object->world_rest_mesh();
  const TriMesh& world = object->world_mesh ? *object->world_mesh : fallback;
  // The target object only, and only its triangles under the stroke (same first hits, a much smaller BVH).
  const RayCaster rays = stroke_ray_caster(world, camera, p_.stroke, BuildQuality::high);
  const std::optional<IncisionFrame> frame = fit_incision_frame(p_.stroke, camera, rays);
  if (!frame) throw CommandError("field 'stroke': the stroke misses the surface of '" + p_.object + "'", "stroke");
  IncisionResult r = [&] {
    try {
      return incise(world, *frame, incision_params(p_));
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      const std::size_t colon = msg.find(':');
      std::string field = colon == std::string::npos ? "stroke" : msg.substr(0, colon);
      if (field == "eps") field = "stroke";
      throw CommandError("field '" + field + "': " + (colon == std::string::npos ? msg : msg.substr(colon + 2)), field);
    }
  }();
  if (r.cut_edges == 0)
    throw CommandError("field 'stroke': the cut crosses no edge of '" + p_.object + "' (stroke too short?)", "stroke");

  // Back to object space: only what the cut moved or added; the rest keeps its rest values bit for bit.
  const TriMesh& rest = *object->rest_mesh;
  TriMesh out = std::move(r.mesh);
  const glm::dmat4 m = object->transform.matrix();
  const bool identity = object->transform.is_identity();
  const glm::dmat4 inv = glm::inverse(m);
  const glm::dmat3 nrm_back = glm::transpose(glm::dmat3(m));  // inverse transpose of T⁻¹'s linear part
  const bool flip = glm::determinant(glm::dmat3(m)) < 0.0;
  // (With the identity, T(rest) is rest itself: nothing to map.)
  for (std::size_t v = 0; !identity && v < out.positions.size(); ++v) {
    if (v < rest.positions.size() && !r.moved[v]) {
      out.positions[v] = rest.positions[v];
      if (!out.normals.empty() && rest.normals.size() == rest.positions.size()) out.normals[v] = rest.normals[v];
      if (!out.uvs.empty() && rest.uvs.size() == rest.positions.size()) out.uvs[v] = rest.uvs[v];
      continue;
    }
    out.positions[v] = glm::dvec3(inv * glm::dvec4(out.positions[v], 1.0));
    if (!out.normals.empty()) {
      const glm::dvec3 q = nrm_back * out.normals[v];
      const double len = glm::length(q);
      if (len > 0.0) out.normals[v] = q / len;
    }
  }
  if (flip)
    for (auto& f : out.triangles) std::swap(f.y, f.z);
  // The opening's morph channel (incision.animate): the cut without its opening, in object space as above; shown
  // fully open (weight 1) until keyed. A new cut replaces the previous incision's channel (that one stays open).
  auto morph = std::make_shared<MorphChannel>();
  morph->what = "incision opening";
  morph->weight_keys = {OffsetKey{0.0, glm::dvec3(1.0, 0.0, 0.0), KeyInterpolation::constant}};
  morph->base_positions = std::move(r.closed);
  for (std::size_t v = 0; !identity && v < morph->base_positions.size(); ++v)
    morph->base_positions[v] = v < rest.positions.size() && !r.moved[v]
                                   ? rest.positions[v]
                                   : glm::dvec3(inv * glm::dvec4(morph->base_positions[v], 1.0));

  SceneObject cut = *object;
  const std::size_t before = rest.positions.size();
  cut.rest_mesh = std::make_shared<const TriMesh>(std::move(out));
  if (morph->base_positions.size() == cut.rest_mesh->positions.size()) cut.morph = std::move(morph);
  cut.refresh();
  stats_ = {{"hits", frame->hits.size()},
            {"embedded_vertices", r.embedded_vertices},
            {"newton_fallbacks", r.newton_fallbacks},
            {"cut_edges", r.cut_edges},
            {"split_faces", r.split_faces},
            {"tips", r.tips},
            {"wall_faces", r.wall_faces},
            {"controls", {r.controls.x, r.controls.y, r.controls.z}},
            {"vertices_before", before},
            {"vertices_after", cut.rest_mesh->positions.size()},
            {"ms", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return cut;
}

}  // namespace trispline::core
