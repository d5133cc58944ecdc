#include "core/commands/object_transform.h"

#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>

#include "core/params/codecs.h"

namespace trispline::core {

namespace {

void check_components(const glm::dvec3& v, const char* field, double lo, double hi, bool open_lo,
                      const std::string& what) {
  for (int a = 0; a < 3; ++a) {
    const double x = v[a];
    if (!std::isfinite(x) || x > hi || x < lo || (open_lo && x == lo))
      throw CommandError("field '" + std::string(field) + "': component " + std::string(1, char('x' + a)) + " = " +
                             params::format_number(x) + " " + what,
                         field);
  }
}

// An affine map of world space: y = linear·x + shift.
struct Affine {
  glm::dmat3 linear{1.0};
  glm::dvec3 shift{0.0};
  glm::dvec3 apply(const glm::dvec3& x) const { return linear * x + shift; }
};

// A = M(after)·M(before)⁻¹, from the two transforms' linear parts (so a pure translation stays exactly one).
Affine change_between(const Transform& before, const Transform& after) {
  const glm::dmat4 mb = before.matrix(), ma = after.matrix();
  const glm::dmat3 lb(mb), la(ma);
  Affine a;
  a.linear = la * glm::inverse(lb);
  if (before.rotate_deg == after.rotate_deg && before.scale == after.scale) a.linear = glm::dmat3(1.0);
  a.shift = glm::dvec3(ma[3]) - a.linear * glm::dvec3(mb[3]);
  return a;
}

TriMesh mapped(const TriMesh& mesh, const Affine& a) {
  TriMesh out = mesh;
  const glm::dmat3 nrm = glm::inverseTranspose(a.linear);
  for (auto& p : out.positions) p = a.apply(p);
  for (auto& n : out.normals) {
    const glm::dvec3 q = nrm * n;
    const double len = glm::length(q);
    if (len > 0) n = q / len;
  }
  if (glm::determinant(a.linear) < 0)
    for (auto& f : out.triangles) std::swap(f.y, f.z);
  return out;
}

// E' = E ∘ A⁻¹: the moved rest positions get the parameters the old ones had.
Embedding mapped(const Embedding& e, const Affine& a) {
  const glm::dmat3 inv = glm::inverse(a.linear);
  Embedding out;
  out.linear = e.linear * inv;
  out.offset = e.offset - out.linear * a.shift;
  return out;
}

template <class Lattice>
void map_control_points(Lattice& lattice, const Affine& a) {
  for (glm::dvec3& p : lattice.control_points()) p = a.apply(p);
}

}  // namespace

void check_transform(const Transform& t) {
  check_components(t.translate, "translate", -kMaxTranslate, kMaxTranslate, false,
                   "is not a finite number within ±1e9 world units");
  check_components(t.rotate_deg, "rotate_deg", -kMaxRotateDeg, kMaxRotateDeg, false,
                   "is not a finite angle within ±1e6 degrees");
  check_components(t.scale, "scale", 0.0, kMaxScale, true, "is not a finite number in (0, 1e6]");
}

SceneObject object_with_transform(const SceneObject& object, const Transform& t, bool exact) {
  const Affine a = change_between(object.transform, t);
  const bool has_lattice = object.ffd || object.dffd;
  if (has_lattice && !(glm::determinant(a.linear) > 0))
    throw CommandError("field 'scale': '" + object.name +
                           "' has a lattice and this scale would mirror it (the sign of a scale component changes); "
                           "keep the signs of its scale",
                       "scale");
  SceneObject out = object;
  out.transform = t;
  if (object.ffd) {
    auto binding = std::make_shared<FfdBinding>(*object.ffd);
    map_control_points(binding->lattice, a);
    binding->embedding = mapped(binding->embedding, a);
    out.ffd = std::move(binding);
  }
  if (object.dffd) {
    auto rig = std::make_shared<DffdRig>(*object.dffd);
    map_control_points(rig->lattice, a);
    if (rig->seam) {
      auto seam = std::make_shared<DffdSeam>(*rig->seam);
      for (glm::dvec3& p : seam->open_points) p = a.apply(p);
      for (glm::dvec3& p : seam->stitched_points) p = a.apply(p);
      rig->seam = std::move(seam);
    }
    rig->embedding = mapped(rig->embedding, a);
    for (glm::dvec3& p : rig->fold_points) p = a.apply(p);
    out.dffd = std::move(rig);
  }
  if (object.placement) {  // the contact samples are world points; the stroke stays where it was drawn (pixels)
    auto record = std::make_shared<PlacementRecord>(*object.placement);
    for (glm::dvec3& p : record->contact_points) p = a.apply(p);
    out.placement = std::move(record);
  }
  if (exact)
    out.refresh();
  else if (object.world_mesh)
    out.world_mesh = std::make_shared<const TriMesh>(mapped(*object.world_mesh, a));
  return out;
}

auto ObjectTransformCommand::declare() -> Schema {
  return Schema("object.transform", "Set an object's location, rotation and scale (its lattice moves with it)")
      .field("object", &P::object, {.required = true, .help = "Object id"})
      .field("translate", &P::translate,
             {.range = ParamRange::magnitude_at_most(kMaxTranslate),
              .unit = "world units",
              .default_text = "unchanged",
              .help = "Absolute location"})
      .field("rotate_deg", &P::rotate_deg,
             {.range = ParamRange::magnitude_at_most(kMaxRotateDeg),
              .unit = "degrees",
              .default_text = "unchanged",
              .help = "Absolute rotation about x, then y, then z (R = Rz·Ry·Rx)"})
      .field_as<ScaleCodec>("scale", &P::scale,
                            {.range = ParamRange{0, kMaxScale, true, false},
                             .default_text = "unchanged",
                             .help = "Absolute scale per axis; an object with a lattice keeps the signs of its scale"})
      .label([](const P& p) { return "Transform '" + p.object + "'"; });
}

CommandPtr ObjectTransformCommand::make(const std::string& object, const Transform& t) {
  return std::make_unique<ObjectTransformCommand>(ObjectTransformParams{object, t.translate, t.rotate_deg, t.scale});
}

std::optional<SceneObject> ObjectTransformCommand::build(const Scene& scene) {
  const SceneObject* object = &require_object(scene, p_.object);
  Transform t = object->transform;
  if (p_.translate) t.translate = *p_.translate;
  if (p_.rotate_deg) t.rotate_deg = *p_.rotate_deg;
  if (p_.scale) t.scale = *p_.scale;
  check_transform(
      Transform{t.translate, t.rotate_deg, p_.scale ? *p_.scale : glm::dvec3(1.0)});  // kept scales may be < 0
  const auto t0 = std::chrono::steady_clock::now();
  SceneObject out = object_with_transform(*object, t);
  for (const glm::dvec3& p : out.world_mesh->positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      const char* field = (p_.scale && *p_.scale != object->transform.scale) || !p_.translate ? "scale" : "translate";
      throw CommandError("field '" + std::string(field) + "': '" + p_.object +
                             "' would get non-finite vertices (its extent times this transform overflows)",
                         field);
    }
  stats_ = {{"vertices", out.world_mesh->positions.size()},
            {"lattice_moved", object->ffd || object->dffd ? 1 : 0},
            {"ms_evaluate", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()}};
  return out;
}

}  // namespace trispline::core
