// RayCaster through Embree 3: one shared device, one scene per RayCaster, one triangle geometry per mesh (attached
// by the mesh's index, so Embree's geomID is ours). Embree works in float; the hit returned here is recomputed in
// double from Embree's barycentrics on the double-precision triangle.
#include "core/raycast/ray_caster.h"

#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

namespace trispline::core {
namespace {

void embree_error(void*, RTCError code, const char* str) {
  // Errors are also returned through rtcGetDeviceError; this callback only keeps Embree from printing.
  (void)code;
  (void)str;
}

// One device per process (creating one starts Embree's task system: a few ms). Retained by every RayCaster.
RTCDevice shared_device() {
  static std::mutex mutex;
  static RTCDevice device = nullptr;
  std::lock_guard<std::mutex> lock(mutex);
  if (!device) {
    device = rtcNewDevice(nullptr);
    if (!device)
      throw std::runtime_error("Embree: cannot create device (error " + std::to_string(rtcGetDeviceError(nullptr)) +
                               ")");
    rtcSetDeviceErrorFunction(device, embree_error, nullptr);
  }
  rtcRetainDevice(device);
  return device;
}

}  // namespace

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<TriMesh> meshes;  // positions + triangles only, world units
  bool committed = false;
  bool any_triangles = false;

  RTCBuildQuality quality = RTC_BUILD_QUALITY_HIGH;
  explicit Impl(BuildQuality q) : device(shared_device()) {
    quality = q == BuildQuality::high ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM;
    scene = rtcNewScene(device);
    if (!scene) throw std::runtime_error("Embree: cannot create scene");
    // Robust: watertight-ish traversal (no rays slipping between adjacent triangles); high quality SAH build.
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, quality);
  }
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

RayCaster::RayCaster(BuildQuality quality) : impl_(std::make_unique<Impl>(quality)) {}
RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

int RayCaster::add_mesh(const TriMesh& world_mesh) {
  if (impl_->committed) throw std::logic_error("RayCaster::add_mesh after commit");
  const auto nv = world_mesh.positions.size();
  for (std::size_t i = 0; i < nv; ++i) {
    const auto& p = world_mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("RayCaster::add_mesh: non-finite position at vertex " + std::to_string(i));
  }
  for (const auto& t : world_mesh.triangles)
    if (t.x >= nv || t.y >= nv || t.z >= nv)
      throw std::invalid_argument("RayCaster::add_mesh: triangle index out of range");
  const int id = static_cast<int>(impl_->meshes.size());
  TriMesh copy;
  copy.positions = world_mesh.positions;
  copy.triangles = world_mesh.triangles;
  impl_->meshes.push_back(std::move(copy));
  if (world_mesh.triangles.empty()) return id;  // never hit; no Embree geometry (it would be empty)

  RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                            3 * sizeof(unsigned), world_mesh.triangles.size()));
  if (!vb || !ib) {
    rtcReleaseGeometry(geom);
    throw std::runtime_error("Embree: cannot allocate geometry buffers");
  }
  for (std::size_t i = 0; i < nv; ++i)
    for (int c = 0; c < 3; ++c) vb[3 * i + c] = static_cast<float>(world_mesh.positions[i][c]);
  for (std::size_t f = 0; f < world_mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) ib[3 * f + c] = world_mesh.triangles[f][c];
  rtcSetGeometryBuildQuality(geom, impl_->quality);
  rtcCommitGeometry(geom);
  rtcAttachGeometryByID(impl_->scene, geom, static_cast<unsigned>(id));
  rtcReleaseGeometry(geom);
  impl_->any_triangles = true;
  return id;
}

void RayCaster::commit() {
  rtcCommitScene(impl_->scene);
  const RTCError err = rtcGetDeviceError(impl_->device);
  if (err != RTC_ERROR_NONE)
    throw std::runtime_error("Embree: scene commit failed (error " + std::to_string(err) + ")");
  impl_->committed = true;
}

bool RayCaster::empty() const { return !impl_->any_triangles; }

std::optional<RayHit> RayCaster::intersect(const glm::dvec3& origin, const glm::dvec3& dir, double t_min,
                                           double t_max) const {
  if (!impl_->committed) throw std::logic_error("RayCaster::intersect before commit");
  const double len = glm::length(dir);
  if (!(len > 0) || !std::isfinite(len)) return std::nullopt;
  const glm::dvec3 d = dir / len;
  if (!impl_->any_triangles || !(t_max > t_min)) return std::nullopt;

  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(origin.x);
  rh.ray.org_y = static_cast<float>(origin.y);
  rh.ray.org_z = static_cast<float>(origin.z);
  rh.ray.dir_x = static_cast<float>(d.x);
  rh.ray.dir_y = static_cast<float>(d.y);
  rh.ray.dir_z = static_cast<float>(d.z);
  rh.ray.tnear = static_cast<float>(std::max(0.0, t_min));
  rh.ray.tfar =
      t_max >= std::numeric_limits<float>::max() ? std::numeric_limits<float>::infinity() : static_cast<float>(t_max);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.flags = 0;
  rh.ray.time = 0.0f;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

  const TriMesh& m = impl_->meshes[rh.hit.geomID];
  const glm::uvec3 tri = m.triangles[rh.hit.primID];
  const glm::dvec3 &a = m.positions[tri.x], &b = m.positions[tri.y], &c = m.positions[tri.z];
  const double u = rh.hit.u, v = rh.hit.v;
  RayHit hit;
  hit.geometry = static_cast<int>(rh.hit.geomID);
  hit.triangle = static_cast<int>(rh.hit.primID);
  // Double-precision plane intersection of the ray with the hit triangle; Embree's (float) point if the ray is
  // (nearly) parallel to the plane.
  glm::dvec3 n = glm::cross(b - a, c - a);
  const double nlen = glm::length(n);
  const double denom = glm::dot(n, d);
  if (nlen > 0 && std::abs(denom) > 1e-12 * nlen) {
    hit.t = glm::dot(n, a - origin) / denom;
    hit.position = origin + hit.t * d;
  } else {
    hit.position = (1.0 - u - v) * a + u * b + v * c;
    hit.t = glm::dot(hit.position - origin, d);
  }
  if (nlen > 0) {
    n /= nlen;
    if (glm::dot(n, d) > 0) n = -n;
  }
  hit.normal = n;
  return hit;
}

std::vector<std::optional<RayHit>> RayCaster::intersect_all(const std::vector<glm::dvec3>& origins,
                                                            const std::vector<glm::dvec3>& dirs) const {
  if (origins.size() != dirs.size())
    throw std::invalid_argument("RayCaster::intersect_all: " + std::to_string(origins.size()) + " origins for " +
                                std::to_string(dirs.size()) + " directions");
  std::vector<std::optional<RayHit>> out(origins.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, origins.size(), 64), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) out[i] = intersect(origins[i], dirs[i]);
  });
  return out;
}

}  // namespace trispline::core
