#include "core/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

namespace trispline::core {

glm::dmat4 Transform::matrix() const {
  glm::dmat4 m(1.0);
  m = glm::translate(m, translate);
  m = glm::rotate(m, glm::radians(rotate_deg.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(rotate_deg.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(rotate_deg.x), glm::dvec3(1, 0, 0));
  m = glm::scale(m, scale);
  return m;
}

bool Transform::is_identity() const {
  return translate == glm::dvec3(0.0) && rotate_deg == glm::dvec3(0.0) && scale == glm::dvec3(1.0);
}

TriMesh transformed(const TriMesh& mesh, const Transform& t) {
  if (t.is_identity()) return mesh;
  TriMesh out = mesh;
  const glm::dmat4 m = t.matrix();
  const glm::dmat3 lin(m);
  const glm::dmat3 nrm = glm::inverseTranspose(lin);
  for (auto& p : out.positions) p = glm::dvec3(m * glm::dvec4(p, 1.0));
  for (auto& n : out.normals) {
    const glm::dvec3 q = nrm * n;
    const double len = glm::length(q);
    if (len > 0) n = q / len;
  }
  if (glm::determinant(lin) < 0)
    for (auto& f : out.triangles) std::swap(f.y, f.z);
  return out;
}

TriMesh SceneObject::world_rest_mesh() const {
  if (!rest_mesh) throw std::invalid_argument("object '" + name + "' has no mesh");
  return transformed(*rest_mesh, transform);
}

std::shared_ptr<const MaterialSet> inside_material(const SceneObject& o) {
  if (!o.inside_texture || !o.inside_texture->readable()) return nullptr;
  auto set = std::make_shared<MaterialSet>();
  Material m;
  m.name = o.name + ".inside";
  m.base_color = glm::dvec4(glm::dvec3(o.inside_color), 1.0);
  m.base_color_texture.image = 0;
  m.metallic = 0.0;
  m.roughness = 0.8;
  m.double_sided = true;
  set->materials.push_back(std::move(m));
  set->images.push_back(o.inside_texture);
  return set;
}

TriMesh morphed(const TriMesh& rest, const MorphChannel& morph, double s) {
  if (!std::isfinite(s)) throw std::invalid_argument("morph weight is not finite");
  if (morph.base_positions.size() != rest.positions.size() ||
      (!morph.base_normals.empty() && morph.base_normals.size() != rest.positions.size()))
    throw std::invalid_argument("morph: " + std::to_string(morph.base_positions.size()) + " base positions for " +
                                std::to_string(rest.positions.size()) + " vertices");
  TriMesh out = rest;
  if (s == 1.0) return out;
  const double k = s - 1.0;
  for (std::size_t v = 0; v < out.positions.size(); ++v)
    out.positions[v] = rest.positions[v] + k * (rest.positions[v] - morph.base_positions[v]);
  if (!morph.base_normals.empty() && rest.normals.size() == rest.positions.size())
    for (std::size_t v = 0; v < out.normals.size(); ++v) {
      const glm::dvec3 n = rest.normals[v] + k * (rest.normals[v] - morph.base_normals[v]);
      const double len = glm::length(n);
      if (len > 0.0) out.normals[v] = n / len;
    }
  return out;
}

namespace {
SceneObject posed_by_clip(const SceneObject& object, double time_s);
}  // namespace

void SceneObject::refresh() {
  if (clip || morph) {  // the pose at scene time 0, so world_mesh always equals scene_at_time(·, 0)'s
    SceneObject posed = posed_by_clip(*this, 0.0);
    posed.refresh();
    world_mesh = std::move(posed.world_mesh);
    return;
  }
  if (!dffd && !ffd && transform.is_identity()) {  // world = rest exactly (transformed() copies): share it
    if (!rest_mesh) throw std::invalid_argument("object '" + name + "' has no mesh");
    world_mesh = rest_mesh;
    return;
  }
  TriMesh rest = world_rest_mesh();
  if (dffd) {
    if (ffd) throw std::invalid_argument("object '" + name + "' has both an FFD and a DFFD binding");
    if (dffd->params.size() != rest.positions.size())
      throw std::invalid_argument("object '" + name + "': DFFD binding has " + std::to_string(dffd->params.size()) +
                                  " parameters for " + std::to_string(rest.positions.size()) + " vertices");
    const std::shared_ptr<const DffdRig> rig = dffd_rig_at(dffd, 0.0);
    world_mesh =
        std::make_shared<const TriMesh>(dffd_apply(*rig, rest, offset_at(0.0), nullptr, cap_texturing_of(*rig)));
  } else if (ffd) {
    if (ffd->params.size() != rest.positions.size())
      throw std::invalid_argument("object '" + name + "': FFD binding has " + std::to_string(ffd->params.size()) +
                                  " parameters for " + std::to_string(rest.positions.size()) + " vertices");
    const glm::dvec3 offset = offset_at(0.0);  // the t = 0 pose (keys, when there are any, replace param_offset)
    if (offset == glm::dvec3(0.0)) {
      world_mesh = std::make_shared<const TriMesh>(ffd_apply(*ffd, rest));
    } else {
      if (!std::isfinite(offset.x) || !std::isfinite(offset.y) || !std::isfinite(offset.z))
        throw std::invalid_argument("object '" + name + "': parameter offset is not finite");
      FfdBinding shifted = *ffd;  // parameters outside [0,1] are clamped, or wrap on periodic axes
      for (glm::dvec3& p : shifted.params) p += offset;
      world_mesh = std::make_shared<const TriMesh>(ffd_apply(shifted, rest));
    }
  } else {
    world_mesh = std::make_shared<const TriMesh>(std::move(rest));
  }
}

namespace {
// `object` (with a clip or a morph) posed at `time_s`: the clip's positions/normals (or the morph at its weight) as
// rest mesh, FFD parameters re-embedded with the same embedding, clip and morph removed. world_mesh is not refreshed.
SceneObject posed_by_clip(const SceneObject& object, double time_s) {
  SceneObject moved = object;
  TriMesh posed;
  if (object.clip) {
    posed = *object.rest_mesh;  // topology, uvs and names kept; positions and normals from the clip
    object.clip->clip->pose(object.clip->clip_time(time_s), posed.positions, posed.normals);
    if (posed.positions.size() != object.rest_mesh->positions.size())
      throw std::invalid_argument("object '" + object.name + "': clip '" + object.clip->clip->name() + "' poses " +
                                  std::to_string(posed.positions.size()) + " vertices, the mesh has " +
                                  std::to_string(object.rest_mesh->positions.size()));
  } else {
    try {
      posed = morphed(*object.rest_mesh, *object.morph, object.morph->weight_at(time_s));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("object '" + object.name + "': " + e.what());
    }
  }
  moved.rest_mesh = std::make_shared<const TriMesh>(std::move(posed));
  moved.clip = nullptr;
  moved.morph = nullptr;
  if (object.ffd) {  // same lattice and embedding, parameters of the posed vertices
    auto binding = std::make_shared<FfdBinding>(*object.ffd);
    binding->params = embed_points(binding->embedding, moved.world_rest_mesh().positions);
    moved.ffd = std::move(binding);
  }
  return moved;
}
}  // namespace

namespace {
// The object's animated tile layers as stills at `time_s` (α, offset, transform, height and an articulated tile's
// pose fixed, mesh evaluated there); false when none is animated.
bool pose_ddm_layers(SceneObject& object, double time_s) {
  bool any = false;
  for (auto& layer : object.ddm_layers) {
    if (!layer->animated()) continue;
    auto still = std::make_shared<DdmLayer>(*layer);
    still->alpha = layer->alpha_at(time_s);
    still->alpha_keys.clear();
    still->offset_keys = {OffsetKey{0.0, glm::dvec3(layer->offset_at(time_s), 0.0), KeyInterpolation::constant}};
    still->offset_velocity = glm::dvec2(0.0);
    still->transform = layer->transform_at(time_s), still->height = layer->height_at(time_s);
    still->rotate_keys.clear(), still->scale_keys.clear(), still->w_keys.clear();
    if (layer->tile_clip) still->tiles = layer->tiles_at_time(time_s), still->tile_clip = nullptr;  // posed, still
    still->mesh = std::make_shared<const TriMesh>(ddm_layer_mesh(*layer, time_s));
    layer = std::move(still);
    any = true;
  }
  return any;
}

// `moved` (a copy of `object`) with its parameter offset (and a DFFD's keyed seam) fixed at `time_s`: no keys, no
// velocity.
void freeze_offset(SceneObject& moved, const SceneObject& object, double time_s) {
  moved.param_offset = object.offset_at(time_s);
  moved.offset_keys.clear();
  moved.offset_velocity = glm::dvec3(0.0);
  if (object.dffd) moved.dffd = dffd_rig_at(object.dffd, time_s);
}
}  // namespace

Scene scene_at_time(const Scene& scene, double time_s) {
  if (!std::isfinite(time_s)) throw std::invalid_argument("scene time is not finite");
  Scene out = scene;
  for (const SceneObject& object : scene.objects()) {
    if (!object.animated()) {
      SceneObject posed = object;  // tile layers animate on their own (ddm.animate); the object stays as it is
      if (pose_ddm_layers(posed, time_s)) out.replace(std::move(posed));
      continue;
    }
    SceneObject moved = object.clip || object.morph ? posed_by_clip(object, time_s) : object;
    pose_ddm_layers(moved, time_s);
    freeze_offset(moved, object, time_s);
    moved.refresh();
    out.replace(std::move(moved));
  }
  return out;
}

Scene scene_with_posed_clips(const Scene& scene, double time_s) {
  if (!std::isfinite(time_s)) throw std::invalid_argument("scene time is not finite");
  Scene out = scene;
  for (const SceneObject& object : scene.objects()) {
    if (!object.cpu_animated()) continue;
    SceneObject moved = object.clip || object.morph ? posed_by_clip(object, time_s) : object;
    if (object.dffd_animated()) freeze_offset(moved, object, time_s);  // a still at time_s, like scene_at_time
    moved.refresh();
    out.replace(std::move(moved));
  }
  return out;
}

namespace {

// The scene's two named lists (objects, volumes): found by name, kept in order; take_named / replace_named's `kind`
// names the item in their errors ("no volume named …").
template <class T>
int index_in(const std::vector<T>& list, const std::string& name) {
  for (std::size_t i = 0; i < list.size(); ++i)
    if (list[i].name == name) return static_cast<int>(i);
  return -1;
}

template <class T>
void insert_at(std::vector<T>& list, T item, int index) {
  if (index < 0 || index > static_cast<int>(list.size())) index = static_cast<int>(list.size());
  list.insert(list.begin() + index, std::move(item));
}

template <class T>
T take_named(std::vector<T>& list, const std::string& name, const char* kind) {
  const int i = index_in(list, name);
  if (i < 0) throw std::out_of_range(std::string("no ") + kind + " named '" + name + "'");
  T out = std::move(list[i]);
  list.erase(list.begin() + i);
  return out;
}

template <class T>
void replace_named(std::vector<T>& list, T item, const char* kind) {
  const int i = index_in(list, item.name);
  if (i < 0) throw std::out_of_range(std::string("no ") + kind + " named '" + item.name + "'");
  list[i] = std::move(item);
}

}  // namespace

const SceneObject* Scene::find(const std::string& name) const {
  const int i = index_of(name);
  return i < 0 ? nullptr : &objects_[i];
}

SceneObject* Scene::find(const std::string& name) {
  const int i = index_of(name);
  return i < 0 ? nullptr : &objects_[i];
}

int Scene::index_of(const std::string& name) const { return index_in(objects_, name); }

std::string object_name_error(const std::string& name) {
  if (name.empty()) return "a name must not be empty";
  if (name.size() > 256) return "a name must be at most 256 bytes long";
  if (name == "." || name == "..") return "'" + name + "' cannot be a name";
  for (const char c : name) {
    if (c == '/') return "a name must not contain '/' (scene.glb names a tile layer '<object>/<layer>')";
    if ((unsigned char)c < 0x20 || c == 0x7F) return "a name must not contain control characters (NUL, tab, newline)";
  }
  return {};
}

std::string sanitized_object_name(const std::string& name) {
  std::string out;
  for (const char c : name) out.push_back(c == '/' || (unsigned char)c < 0x20 || c == 0x7F ? '_' : c);
  if (out.size() > 256) {
    std::size_t cut = 256;
    while (cut > 0 && ((unsigned char)out[cut] & 0xC0) == 0x80) --cut;  // not inside a UTF-8 sequence
    out.resize(cut);
  }
  if (out.empty() || out == "." || out == "..") out = "object";
  return out;
}

void Scene::insert(SceneObject object, int index) {
  if (const std::string bad = object_name_error(object.name); !bad.empty()) throw std::invalid_argument(bad);
  if (index_of(object.name) >= 0 || volume_index_of(object.name) >= 0)
    throw std::invalid_argument("an object named '" + object.name + "' already exists");
  insert_at(objects_, std::move(object), index);
}

SceneObject Scene::remove(const std::string& name) { return take_named(objects_, name, "object"); }

void Scene::replace(SceneObject object) { replace_named(objects_, std::move(object), "object"); }

void Scene::clear() {
  objects_.clear();
  volumes_.clear();
  camera = Camera{};
  camera_set = false;
}

Aabb Scene::bounds() const {
  Aabb box;
  for (const auto& o : objects_)
    if (o.visible && o.world_mesh)
      for (const auto& p : o.world_mesh->positions) box.extend(p);
  for (const auto& v : volumes_)
    if (v.visible) {
      const Aabb b = v.world_bounds();
      box.extend(b.lo), box.extend(b.hi);
    }
  return box;
}

const VolumeObject* Scene::find_volume(const std::string& name) const {
  const int i = volume_index_of(name);
  return i < 0 ? nullptr : &volumes_[i];
}

int Scene::volume_index_of(const std::string& name) const { return index_in(volumes_, name); }

void Scene::insert_volume(VolumeObject volume, int index) {
  if (const std::string bad = object_name_error(volume.name); !bad.empty()) throw std::invalid_argument(bad);
  if (index_of(volume.name) >= 0 || volume_index_of(volume.name) >= 0)
    throw std::invalid_argument("an object named '" + volume.name + "' already exists");
  if (!volume.spline || !volume.table) throw std::invalid_argument("a volume needs its spline and singleton table");
  insert_at(volumes_, std::move(volume), index);
}

VolumeObject Scene::remove_volume(const std::string& name) { return take_named(volumes_, name, "volume"); }

void Scene::replace_volume(VolumeObject volume) { replace_named(volumes_, std::move(volume), "volume"); }

Aabb VolumeObject::world_bounds() const {
  Aabb box;
  const auto& d = spline->dims();
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 ijk((c & 1) ? d[0] - 1 : 0, (c & 2) ? d[1] - 1 : 0, (c & 4) ? d[2] - 1 : 0);
    box.extend(glm::dvec3(spline->index_to_world() * glm::dvec4(ijk, 1.0)));
  }
  return box;
}

SilhouetteView VolumeObject::silhouette_view(const Camera& camera) const {
  SilhouetteView v;
  v.perspective = silhouette.projection != "orthographic";
  v.eye = camera.eye;
  v.direction = camera.forward();
  return v;
}

SilhouetteView VolumeObject::screen_silhouette_view(const Camera& camera) const {
  SilhouetteView v = silhouette_view(camera);
  const double at_unit = 2.0 * std::tan(glm::radians(camera.fov_deg) * 0.5) / std::max(camera.viewport.y, 1);
  // Orthographic silhouettes of a perspective camera: the pixel size at the target.
  v.pixel_size = v.perspective ? at_unit : at_unit * glm::length(camera.target - camera.eye);
  return v;
}

std::string Scene::unique_name(const std::string& base) const {
  if (index_of(base) < 0 && volume_index_of(base) < 0) return base;
  for (int i = 1;; ++i) {
    char buf[16];
    std::snprintf(buf, sizeof buf, ".%03d", i);
    if (index_of(base + buf) < 0 && volume_index_of(base + buf) < 0) return base + buf;
  }
}

glm::vec3 palette_color(int i) {
  // Okabe–Ito palette, lightened slightly for shading.
  static const glm::vec3 colors[] = {{0.90f, 0.62f, 0.00f}, {0.34f, 0.71f, 0.91f}, {0.00f, 0.62f, 0.45f},
                                     {0.94f, 0.89f, 0.26f}, {0.00f, 0.45f, 0.70f}, {0.84f, 0.37f, 0.00f},
                                     {0.80f, 0.47f, 0.65f}, {0.75f, 0.75f, 0.75f}};
  return colors[((i % 8) + 8) % 8];
}

}  // namespace trispline::core
