#include "core/commands/dffd_split.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>

#include "core/dffd/obstacle_interior.h"
#include "core/params/codecs.h"

namespace trispline::core {

namespace {

constexpr int kClearanceRounds = 4, kKernelWidenings = 3;

struct SplitAttempt {
  explicit SplitAttempt(GlobalDffd b) : built(std::move(b)) {}
  GlobalDffd built;
  std::shared_ptr<const DffdRig> rig;
  TriMesh mesh;
  DffdApplyStats st;
  ObstacleIntrusion intrusion;             // the state the line asks for
  std::optional<ObstacleIntrusion> other;  // the seam's other state (cap ↔ stitch)
  // How deep the deepest vertex inside an obstacle is, over both states.
  double max_depth() const { return std::max(intrusion.max_depth, other ? other->max_depth : 0.0); }
};

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

const ParamSchema<Aabb>& box_schema() {
  static const ParamSchema<Aabb> s =
      ParamSchema<Aabb>("box", "An axis-aligned box")
          .field("lo", &Aabb::lo, {.required = true, .unit = "world units", .help = "Lowest corner"})
          .field("hi", &Aabb::hi, {.required = true, .unit = "world units", .help = "Highest corner"});
  return s;
}

// The object dffd.split may split: neither deformed by an FFD lattice nor playing a glTF clip (CommandError "object").
void check_splittable(const SceneObject& object, const std::string& id) {
  if (object.ffd)
    throw CommandError("field 'object': '" + id +
                           "' is deformed by an FFD lattice; dffd.split builds its own "
                           "lattice around the obstacles (split an undeformed object)",
                       "object");
  if (object.clip)
    throw CommandError("field 'object': '" + id +
                           "' plays a glTF clip; splitting would break its vertex "
                           "correspondence (remove the clip first)",
                       "object");
}

// The obstacles' world meshes, in the order of `ids` (CommandError "obstacles": unknown id, or an object without a
// mesh).
std::vector<DffdObstacle> split_obstacles(const Scene& scene, const std::vector<std::string>& ids) {
  std::vector<DffdObstacle> obstacles;
  for (const std::string& id : ids) {
    const SceneObject* o = &require_object(scene, id, "obstacles");
    if (!o->world_mesh || o->world_mesh->empty())
      throw CommandError("field 'obstacles': '" + id + "' has no mesh", "obstacles");
    obstacles.push_back({id, *o->world_mesh});
  }
  return obstacles;
}

// One split with parameters q: the lattice (build_global_dffd; its DffdBuildError as a CommandError), the rig, the
// split mesh and the vertices it leaves inside an obstacle, in the state the line asks for and, with a seam, in the
// other one (the state dffd.animate may key it to). Adds the build and evaluation times to build_ms, eval_ms (ms).
SplitAttempt attempt_split(const TriMesh& rest, const std::vector<DffdObstacle>& obstacles,
                           const ObstacleInterior& interior, const GlobalDffdParams& q, double& build_ms,
                           double& eval_ms) {
  const auto t0 = std::chrono::steady_clock::now();
  SplitAttempt a([&] {
    try {
      return build_global_dffd(rest, obstacles, q);
    } catch (const DffdBuildError& e) {
      throw CommandError("field '" + e.field + "': " + e.what(), e.field);
    }
  }());
  build_ms += ms_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  a.rig = std::make_shared<const DffdRig>(std::move(a.built.rig));
  a.mesh = dffd_apply(*a.rig, rest, q.offset, &a.st);
  eval_ms += ms_since(t1);
  a.intrusion = interior.intrusion(a.mesh.positions);
  if (a.rig->seam) {  // the state dffd.animate may key the seam to
    DffdRig other = *a.rig;
    dffd_set_stitch(other, q.openings == DffdOpenings::stitch ? 0.0 : 1.0);
    a.other = interior.intrusion(dffd_apply(other, rest, q.offset).positions);
  }
  return a;
}

// Caps and stitches need a mesh closed where it is cut (CommandError "openings": the open boundary chains).
void check_openings_closed(const SplitAttempt& a, const GlobalDffdParams& p, const std::string& object) {
  if (a.st.open_chains > 0 && p.openings != DffdOpenings::open)
    throw CommandError(
        "field 'openings': '" + object + "' is not closed where it is cut (" + std::to_string(a.st.open_chains) +
            " open boundary chain(s) on the discontinuity planes), so "
            "its openings cannot be " +
            (p.openings == DffdOpenings::cap ? "capped" : "stitched") + "; use \"openings\":\"open\" or close the mesh",
        "openings");
}

// The clearance rounds build() describes, at most kClearanceRounds, κ widened at most kKernelWidenings times a round:
// `a` and `p` end as the last attempt and its parameters; returns the rounds run. CommandError "clearance" when a
// round fails otherwise.
template <class Attempt>
int refine_clearance(SplitAttempt& a, GlobalDffdParams& p, const Attempt& attempt, const std::string& object) {
  std::size_t other_before = SIZE_MAX;
  auto other_helped = [&] { return a.other && a.other->inside > 0 && a.other->inside < other_before; };
  int rounds = 0;
  for (; rounds < kClearanceRounds && (a.intrusion.inside > 0 || other_helped()); ++rounds) {
    GlobalDffdParams q = p;
    q.clearance += 1.5 * (other_helped() ? a.max_depth() : a.intrusion.max_depth);
    q.controls.y = std::min(64, 2 * q.controls.y), q.controls.z = std::min(64, 2 * q.controls.z);
    other_before = a.other ? a.other->inside : 0;
    for (int widened = 0;; ++widened) {
      try {
        a = attempt(q);
        break;
      } catch (const CommandError& e) {
        if (e.field() == "kernel_width" && widened < kKernelWidenings) {
          q.kernel_width *= 1.5;
          continue;
        }
        throw CommandError("field 'clearance': " + std::to_string(a.intrusion.inside) + " vertices of '" + object +
                               "' lie inside '" + a.intrusion.deepest_obstacle + "' (up to " +
                               short_number(a.intrusion.max_depth) + " world units deep), and refining the " +
                               "lattice to clear them failed: " + e.what() + "; give a clearance or more controls",
                           "clearance");
      }
    }
    p = q;
  }
  return rounds;
}

// No vertex may stay inside an obstacle after the rounds (CommandError "clearance": how many, how deep, what was
// tried).
void check_cleared(const SplitAttempt& a, const GlobalDffdParams& p, const std::string& object) {
  if (a.intrusion.inside > 0)
    throw CommandError("field 'clearance': " + std::to_string(a.intrusion.inside) + " vertices of '" + object +
                           "' stay inside '" + a.intrusion.deepest_obstacle + "' (up to " +
                           short_number(a.intrusion.max_depth) + " world units deep) after " +
                           std::to_string(kClearanceRounds) + " refinements (clearance " + short_number(p.clearance) +
                           ", controls [" + std::to_string(p.controls.x) + "," + std::to_string(p.controls.y) + "," +
                           std::to_string(p.controls.z) + "]); give a larger clearance or more controls",
                       "clearance");
}

// report.json of dffd.split (the keys and their order as the header lists them): the split `out` of `rest` by the
// last attempt `a` with parameters `p`, after `rounds` clearance rounds; build_ms, eval_ms over every attempt.
nlohmann::json dffd_split_report(const SplitAttempt& a, const SceneObject& out, const TriMesh& rest,
                                 std::size_t inside_before, int rounds, const GlobalDffdParams& p,
                                 const ObstacleInterior& interior, double build_ms, double eval_ms) {
  const GlobalDffd& built = a.built;
  const DffdApplyStats& st = a.st;
  return {{"discontinuities", out.dffd->discontinuities.size()},
          {"v_knots", built.v_knots},
          {"projected_points", built.projected_points},
          {"max_displacement", built.max_displacement},
          {"fold_overs", built.folds.size()},
          {"w_s", built.w_s},
          {"cut_edges", st.cut_edges},
          {"cap_loops", st.cap_loops},
          {"open_chains", st.open_chains},
          {"cap_triangles", st.cap_triangles},
          {"outside_vertices", st.outside_vertices},
          {"vertices_before", rest.vertex_count()},
          {"vertices_after", out.world_mesh->vertex_count()},
          {"inside_obstacle", a.intrusion.inside},
          {"inside_obstacle_other_state", a.other ? nlohmann::json(a.other->inside) : nlohmann::json()},
          {"inside_before_refinement", inside_before},
          {"refinement_rounds", rounds},
          {"clearance_used", p.clearance},
          {"controls_used", {p.controls.x, p.controls.y, p.controls.z}},
          {"kernel_width_used", p.kernel_width},
          {"unchecked_obstacles", interior.unchecked()},
          {"build_ms", build_ms},
          {"eval_ms", eval_ms}};
}

}  // namespace

const ParamSchema<GlobalDffdParams>& global_dffd_schema() {
  using G = GlobalDffdParams;
  static const ParamSchema<G> s =
      ParamSchema<G>("dffd", "The lattice of a global DFFD")
          .choice("axis", &G::axis, axis_names(),
                  {.ui = {"Axis (u)"}, .help = "World axis of the lattice's u: the travel direction"})
          .choice("w_axis", &G::w_axis, axis_names(),
                  {.ui = {"W axis (w)"},
                   .help = "World axis of the lattice's w: the slicing planes W_k are orthogonal to it"})
          .check([](const G& g) {
            if (g.axis == g.w_axis) params::fail("w_axis", "must differ from 'axis'");
          })
          .field("order", &G::order,
                 {.range = ParamRange{2, 6},
                  .ui = {"Order", 0.05},
                  .help = "Order (= degree + 1) per lattice axis u, v, w"})
          .field("controls", &G::controls,
                 {.range = ParamRange{2, 64},
                  .ui = {"Controls", 0.1},
                  .help = "Control points per lattice axis before knot insertion, ≥ order"})
          .choice("kernel", &G::kernel, {"gaussian", "bspline"},
                  {.ui = {"Kernel"}, .help = "κ: truncated Gaussian or quadratic B-spline"})
          .field("kernel_width", &G::kernel_width,
                 {.required = true,
                  .range = ParamRange::above(0),
                  .unit = "world units",
                  .ui = {"Kernel width"},
                  .help = "κ's reach along axis (the opening's propagation)"})
          .choice("openings", &G::openings, {"open", "stitch", "cap"},
                  {.ui = {"Openings"},
                   .help = "open: holes; stitch: re-joined behind the obstacle; cap: closed by CGAL-triangulated caps"})
          .choice("fold", &G::reject_fold, {"warn", "reject"},
                  {.ui = {"Fold-over"}, .help = "A fold-over (seed Theorem 6) fails or only warns"})
          .field("margin", &G::margin,
                 {.write = ParamWrite::UnlessDefault,
                  .range = ParamRange::at_least(0),
                  .unit = "world units",
                  .default_text = "1.05 × kernel_width",
                  .ui = {"Margin"},
                  .help = "Lattice growth beyond the obstacles along axis"})
          .field(
              "clearance", &G::clearance,
              {.range = ParamRange::at_least(0),
               .unit = "world units",
               .ui = {"Clearance"},
               .help = "Kept between the wrapped object and the obstacle; where vertices would still lie inside an "
                       "obstacle the split raises it and refines the lattice by itself (report.json: clearance_used)"})
          .field("eps", &G::eps,
                 {.range = ParamRange{0, 1e-3, true, false},
                  .unit = "parameter units",
                  .help = "Cut vertices sit at u0 ∓ eps"})
          .object("box", &G::box, box_schema(), {.help = "The lattice box; every obstacle must lie inside it"});
  return s;
}

auto DffdSplitCommand::declare() -> Schema {
  return Schema("dffd.split",
                "Split an object around obstacles with a global discontinuous FFD; open, stitched "
                "or capped openings (seed §6.3)")
      .field("object", &P::object, {.required = true, .help = "An undeformed object without a glTF clip"})
      .field("obstacles", &P::obstacles, {.required = true, .help = "Ids of other objects (static)"})
      .check([](const P& p) {
        if (p.obstacles.empty()) params::fail("obstacles", "expected a non-empty array of object ids");
        for (std::size_t i = 0; i < p.obstacles.size(); ++i) {
          const std::string& id = p.obstacles[i];
          if (id == p.object) params::fail("obstacles", "'" + id + "' is the object being split");
          if (std::find(p.obstacles.begin(), p.obstacles.begin() + std::ptrdiff_t(i), id) !=
              p.obstacles.begin() + std::ptrdiff_t(i))
            params::fail("obstacles", "'" + id + "' is listed twice");
        }
      })
      .embed(&P::dffd, global_dffd_schema())
      .label([](const P& p) {
        return "Split '" + p.object + "' around " + std::to_string(p.obstacles.size()) + " obstacle" +
               (p.obstacles.size() == 1 ? "" : "s") + " (" + dffd_openings_name(p.dffd.openings) + ")";
      });
}

std::optional<SceneObject> DffdSplitCommand::build(const Scene& scene) {
  const SceneObject* object = &require_object(scene, p_.object);
  check_splittable(*object, p_.object);
  std::vector<DffdObstacle> obstacles = split_obstacles(scene, p_.obstacles);
  const TriMesh rest = object->world_rest_mesh();
  std::vector<std::string> names;
  std::vector<const TriMesh*> meshes;
  for (const DffdObstacle& o : obstacles) names.push_back(o.name), meshes.push_back(&o.world_mesh);
  const ObstacleInterior interior(names, meshes);
  GlobalDffdParams p = p_.dffd;
  p.offset = object->offset_at(0.0);
  double build_ms = 0.0, eval_ms = 0.0;
  auto attempt = [&](const GlobalDffdParams& q) {
    return attempt_split(rest, obstacles, interior, q, build_ms, eval_ms);
  };
  // Clearance: vertices the split leaves inside an obstacle (the lattice's rows fit the cross-section only at their
  // own v and w; between them the spline cuts a chord into it) are cleared in rounds: the controls in v and w doubled
  // (shorter chords) and the clearance raised by 1.5× the deepest one's depth. A round whose larger displacement
  // folds the lattice (seed Theorem 6) is retried with κ 1.5× wider. With a seam (cap, stitch) its other state is
  // cleared too while the rounds help it, so the two splits of one line refine alike; it cannot always be (an
  // obstacle that ends inside the object holds the stitching level) and is then only reported.
  SplitAttempt a = attempt(p);
  check_openings_closed(a, p, p_.object);
  const std::size_t inside_before = a.intrusion.inside;
  const int rounds = refine_clearance(a, p, attempt, p_.object);
  check_cleared(a, p, p_.object);
  SceneObject out = *object;
  out.dffd = a.rig;
  const std::size_t plain_triangles = a.mesh.triangle_count();
  out.world_mesh = std::make_shared<const TriMesh>(std::move(a.mesh));
  if (out.inside_textured()) out.refresh();  // caps with vertices of their own for the inside texture
  stats_ = dffd_split_report(a, out, rest, inside_before, rounds, p, interior, build_ms, eval_ms);
  if (out.inside_textured())  // the caps refined for the inside texture (cap_triangles counts them unrefined)
    stats_["textured_cap_triangles"] = out.world_mesh->triangle_count() - (plain_triangles - a.st.cap_triangles);
  return out;
}

}  // namespace trispline::core
