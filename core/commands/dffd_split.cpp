#include "core/commands/dffd_split.h"

#include <algorithm>
#include <chrono>

#include "core/commands/codecs.h"
#include "core/commands/json_fields.h"

namespace trispline::core {
namespace jf = json_fields;

namespace {
const std::vector<std::string> kAxes = {"x", "y", "z"};
double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

CommandPtr DffdSplitCommand::parse(const nlohmann::json& j, const CommandContext&) {
  auto c = std::make_unique<DffdSplitCommand>();
  c->object_ = jf::get_string(j, "object");
  const nlohmann::json& obs = jf::require(j, "obstacles");
  if (!obs.is_array() || obs.empty())
    throw CommandError("field 'obstacles': expected a non-empty array of object ids", "obstacles");
  for (const auto& o : obs) {
    if (!o.is_string()) throw CommandError("field 'obstacles': expected object ids (strings)", "obstacles");
    const std::string id = o.get<std::string>();
    if (id == c->object_)
      throw CommandError("field 'obstacles': '" + id + "' is the object being split", "obstacles");
    if (std::find(c->obstacles_.begin(), c->obstacles_.end(), id) != c->obstacles_.end())
      throw CommandError("field 'obstacles': '" + id + "' is listed twice", "obstacles");
    c->obstacles_.push_back(id);
  }
  GlobalDffdParams& p = c->params_;
  p.axis = axis_index(jf::get_enum(j, "axis", kAxes, "x"));
  p.w_axis = axis_index(jf::get_enum(j, "w_axis", kAxes, "y"));
  if (p.axis == p.w_axis) throw CommandError("field 'w_axis': must differ from 'axis'", "w_axis");
  p.order = jf::has(j, "order") ? jf::get_ivec3(j, "order") : glm::ivec3(3);
  p.controls = jf::has(j, "controls") ? jf::get_ivec3(j, "controls") : glm::ivec3(12, 8, 8);
  p.kernel = jf::get_enum(j, "kernel", {"gaussian", "bspline"}, "gaussian") == "gaussian" ? DffdKernel::gaussian
                                                                                           : DffdKernel::bspline;
  p.kernel_width = jf::get_number(j, "kernel_width");
  if (!(p.kernel_width > 0.0)) throw CommandError("field 'kernel_width': must be > 0 (world units)", "kernel_width");
  const std::string openings = jf::get_enum(j, "openings", {"open", "stitch", "cap"}, "cap");
  p.openings = openings == "open" ? DffdOpenings::open : openings == "stitch" ? DffdOpenings::stitch : DffdOpenings::cap;
  p.reject_fold = jf::get_enum(j, "fold", {"reject", "warn"}, "reject") == "reject";
  p.margin = jf::get_number(j, "margin", -1.0);
  if (jf::has(j, "margin") && p.margin < 0.0) throw CommandError("field 'margin': must be ≥ 0 (world units)", "margin");
  p.clearance = jf::get_number(j, "clearance", 0.0);
  if (p.clearance < 0.0) throw CommandError("field 'clearance': must be ≥ 0 (world units)", "clearance");
  p.eps = jf::get_number(j, "eps", 1e-6);
  if (!(p.eps > 0.0 && p.eps <= 1e-3)) throw CommandError("field 'eps': must be in (0, 1e-3]", "eps");
  if (jf::has(j, "box")) {
    const nlohmann::json& b = j.at("box");
    if (!b.is_object()) throw CommandError("field 'box': expected {\"lo\":[x,y,z],\"hi\":[x,y,z]}", "box");
    Aabb box;
    box.lo = jf::get_vec3(b, "lo");
    box.hi = jf::get_vec3(b, "hi");
    p.box = box;
  }
  return c;
}

nlohmann::json DffdSplitCommand::to_json() const {
  const GlobalDffdParams& p = params_;
  nlohmann::json j = {{"cmd", id()},
                      {"object", object_},
                      {"obstacles", obstacles_},
                      {"axis", kAxes[p.axis]},
                      {"w_axis", kAxes[p.w_axis]},
                      {"order", jf::to_json(p.order)},
                      {"controls", jf::to_json(p.controls)},
                      {"kernel", p.kernel == DffdKernel::gaussian ? "gaussian" : "bspline"},
                      {"kernel_width", p.kernel_width},
                      {"openings", dffd_openings_name(p.openings)},
                      {"fold", p.reject_fold ? "reject" : "warn"},
                      {"clearance", p.clearance},
                      {"eps", p.eps}};
  if (p.margin >= 0.0) j["margin"] = p.margin;
  if (p.box) j["box"] = {{"lo", jf::to_json(p.box->lo)}, {"hi", jf::to_json(p.box->hi)}};
  return j;
}

std::string DffdSplitCommand::label() const {
  return "Split '" + object_ + "' around " + std::to_string(obstacles_.size()) + " obstacle" +
         (obstacles_.size() == 1 ? "" : "s") + " (" + dffd_openings_name(params_.openings) + ")";
}

std::optional<SceneObject> DffdSplitCommand::build(const Scene& scene) {
  const SceneObject* object = scene.find(object_);
  if (!object) throw CommandError("field 'object': no object named '" + object_ + "'", "object");
  require_no_tile_layers(*object, "a split");
  if (object->ffd)
    throw CommandError("field 'object': '" + object_ + "' is deformed by an FFD lattice; dffd.split builds its own "
                       "lattice around the obstacles (split an undeformed object)", "object");
  if (object->clip)
    throw CommandError("field 'object': '" + object_ + "' plays a glTF clip; splitting would break its vertex "
                       "correspondence (remove the clip first)", "object");
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<DffdObstacle> obstacles;
  for (const std::string& id : obstacles_) {
    const SceneObject* o = scene.find(id);
    if (!o) throw CommandError("field 'obstacles': no object named '" + id + "'", "obstacles");
    if (!o->world_mesh || o->world_mesh->empty())
      throw CommandError("field 'obstacles': '" + id + "' has no mesh", "obstacles");
    obstacles.push_back({id, *o->world_mesh});
  }
  const TriMesh rest = object->world_rest_mesh();
  GlobalDffdParams p = params_;
  p.offset = object->offset_at(0.0);
  GlobalDffd built = [&] {
    try {
      return build_global_dffd(rest, obstacles, p);
    } catch (const DffdBuildError& e) {
      throw CommandError("field '" + e.field + "': " + e.what(), e.field);
    }
  }();
  const double build_ms = ms_since(t0);
  SceneObject out = *object;
  out.dffd = std::make_shared<const DffdRig>(std::move(built.rig));
  const auto t1 = std::chrono::steady_clock::now();
  DffdApplyStats st;
  out.world_mesh = std::make_shared<const TriMesh>(dffd_apply(*out.dffd, rest, p.offset, &st));
  const double eval_ms = ms_since(t1);
  if (st.open_chains > 0 && p.openings != DffdOpenings::open)
    throw CommandError("field 'openings': '" + object_ + "' is not closed where it is cut (" +
                       std::to_string(st.open_chains) + " open boundary chain(s) on the discontinuity planes), so "
                       "its openings cannot be " + (p.openings == DffdOpenings::cap ? "capped" : "stitched") +
                       "; use \"openings\":\"open\" or close the mesh", "openings");
  stats_ = {{"discontinuities", out.dffd->discontinuities.size()},
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
            {"build_ms", build_ms},
            {"eval_ms", eval_ms}};
  return out;
}

}  // namespace trispline::core
