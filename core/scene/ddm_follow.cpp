// Tile layers following their object. See ddm_follow.h.
#include "core/scene/ddm_follow.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "core/ddm/ddm_pn_maps.h"
#include "core/ffd/ffd_fast.h"
#include "core/raycast/ray_caster.h"

namespace trispline::core {
namespace {

glm::dmat3 cofactor(const glm::dmat3& m) {  // det(m)·m⁻ᵀ without dividing: columns are cross products of m's
  return glm::dmat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
}

// The frame of triangle (a, b, c) at a: [b − a, c − a, n̂·√|(b − a)×(c − a)|]; false when degenerate.
bool triangle_frame(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, glm::dmat3& frame) {
  const glm::dvec3 e1 = b - a, e2 = c - a, n = glm::cross(e1, e2);
  const double area2 = glm::length(n);
  if (!(area2 > 0.0) || !std::isfinite(area2)) return false;
  frame = glm::dmat3(e1, e2, n / std::sqrt(area2));
  return true;
}

// The nearest similarity (uniform scale × rotation) to m: the orthogonal polar factor R (Higham's iteration
// R ← ½(R + R⁻ᵀ)) times |det m|^⅓. A triangle stretched or sheared moves its tiles rigidly with it (scaled by its
// size change), so tiles keep their shape; m itself when it is singular or mirrors.
glm::dmat3 similarity_part(const glm::dmat3& m) {
  const double det = glm::determinant(m);
  if (!(det > 0.0) || !std::isfinite(det)) return m;
  glm::dmat3 r = m;
  for (int it = 0; it < 30; ++it) {
    const glm::dmat3 next = 0.5 * (r + glm::transpose(glm::inverse(r)));
    double change = 0.0;
    for (int c = 0; c < 3; ++c) change = std::max(change, glm::length(next[c] - r[c]));
    r = next;
    if (change < 1e-15) break;
  }
  return std::cbrt(det) * r;
}

// The base point at every instance's cell centre (object space, at the layer's texture offset `offset`).
std::vector<DdmSurfacePoint> instance_roots(const DdmLayer& layer, glm::dvec2 offset) {
  const DdmMapsBase base(layer.maps);
  std::vector<DdmSurfacePoint> roots(layer.instances.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, roots.size(), 256), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const DdmInstance& c = layer.instances[i];
      const glm::dvec2 uv = c.origin + 0.5 * c.size + offset;
      roots[i] = base.eval(c.chart, uv.x, uv.y);
    }
  });
  return roots;
}

// Per root: the host mesh triangle under it — the nearer first hit of a ray from just above the root down along −n
// and from just below up along +n; −1 when both miss (then the nearest triangle centroid).
std::vector<int> host_triangles(const TriMesh& host, const std::vector<DdmSurfacePoint>& roots) {
  Aabb box;
  for (const glm::dvec3& p : host.positions) box.extend(p);
  const double reach = 0.05 * std::max(box.diagonal(), 1e-300);
  RayCaster rays(BuildQuality::interactive);
  rays.add_mesh(host);
  rays.commit();
  std::vector<int> out(roots.size(), -1);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, roots.size(), 128), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const glm::dvec3 p = roots[i].p, n = roots[i].n;
      const auto down = rays.intersect(p + reach * n, -n, 0.0, 2.0 * reach);
      const auto up = rays.intersect(p - reach * n, n, 0.0, 2.0 * reach);
      const double dd = down ? std::abs(down->t - reach) : 1e300, du = up ? std::abs(up->t - reach) : 1e300;
      if (down && dd <= du)
        out[i] = down->triangle;
      else if (up)
        out[i] = up->triangle;
      else {  // nearest centroid (rare: a root further than 5 % of the diagonal from the mesh)
        double best = 1e300;
        for (std::size_t f = 0; f < host.triangles.size(); ++f) {
          const glm::uvec3 t = host.triangles[f];
          const glm::dvec3 c = (host.positions[t.x] + host.positions[t.y] + host.positions[t.z]) / 3.0;
          const double d = glm::length(c - p);
          if (d < best) best = d, out[i] = static_cast<int>(f);
        }
      }
    }
  });
  return out;
}

// Host triangles depend only on the host mesh, the maps, the instances and the texture offset, not on the pose: the
// last few are kept (playback of a clip asks every frame). The entries hold the mesh and maps, so their addresses
// cannot be reused while cached.
struct HostKey {
  std::shared_ptr<const TriMesh> host;
  std::shared_ptr<const DdmMaps> maps;
  std::uint64_t instances = 0;  // FNV-1a of the instances' bytes
  glm::dvec2 offset{0.0};
  bool operator==(const HostKey& o) const {
    return host == o.host && maps == o.maps && instances == o.instances && offset == o.offset;
  }
};

std::uint64_t instances_hash(const std::vector<DdmInstance>& instances) {
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&](const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  for (const DdmInstance& c : instances) {
    mix(&c.chart, sizeof c.chart), mix(&c.origin, sizeof c.origin), mix(&c.size, sizeof c.size);
  }
  mix(&h, 0);
  return h ^ instances.size();
}

std::vector<int> cached_host_triangles(const DdmLayer& layer, glm::dvec2 offset,
                                       const std::vector<DdmSurfacePoint>& roots) {
  static std::mutex mutex;
  static std::deque<std::pair<HostKey, std::shared_ptr<const std::vector<int>>>> cache;
  const HostKey key{layer.host_mesh, layer.maps, instances_hash(layer.instances), offset};
  {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& [k, v] : cache)
      if (k == key && v->size() == roots.size()) return *v;
  }
  auto found = std::make_shared<const std::vector<int>>(host_triangles(*layer.host_mesh, roots));
  std::lock_guard<std::mutex> lock(mutex);
  cache.emplace_front(key, found);
  if (cache.size() > 8) cache.pop_back();
  return *found;
}

}  // namespace

std::vector<glm::dvec3> object_surface_positions(const SceneObject& object, double time_s) {
  if (!object.rest_mesh) throw std::invalid_argument("object '" + object.name + "' has no mesh");
  if (object.clip) {
    std::vector<glm::dvec3> positions, normals;
    object.clip->clip->pose(object.clip->clip_time(time_s), positions, normals);
    return positions;
  }
  if (object.morph) return morphed(*object.rest_mesh, *object.morph, object.morph->weight_at(time_s)).positions;
  return object.rest_mesh->positions;
}

DdmLayerDeformation::DdmLayerDeformation(const SceneObject& object, const DdmLayer& layer, double time_s) {
  if (!std::isfinite(time_s)) throw std::invalid_argument("scene time is not finite");
  first_vertex_.assign(layer.instances.size() + 1, 0);
  for (std::size_t i = 0; i < layer.instances.size(); ++i) {
    const int t = layer.instances[i].tile;
    if (t < 0 || t >= static_cast<int>(layer.tiles.size()))
      throw std::invalid_argument("layer '" + layer.name + "': instance tile " + std::to_string(t) + " of " +
                                  std::to_string(layer.tiles.size()));
    first_vertex_[i + 1] = first_vertex_[i] + layer.tiles[static_cast<std::size_t>(t)].mesh.vertex_count();
  }
  model_ = object.transform.matrix();
  flip_ = glm::determinant(glm::dmat3(model_)) < 0.0;
  const bool surface_moves = layer.host_mesh && (object.clip || object.morph || layer.host_mesh != object.rest_mesh);
  const bool has_lattice = object.ffd || object.dffd;
  if (!surface_moves && !has_lattice) return;
  if (!layer.maps) throw std::invalid_argument("layer '" + layer.name + "': no maps");
  const bool sides = object.dffd && !object.dffd->discontinuities.empty();
  const std::vector<DdmSurfacePoint> roots =
      surface_moves || sides ? instance_roots(layer, layer.offset_at(time_s)) : std::vector<DdmSurfacePoint>();

  if (surface_moves) {  // 1. host maps
    const TriMesh& host = *layer.host_mesh;
    const std::vector<glm::dvec3> now = object_surface_positions(object, time_s);
    if (host.positions.size() > now.size())
      throw std::invalid_argument("layer '" + layer.name + "': its host mesh has " +
                                  std::to_string(host.positions.size()) + " vertices, the surface " +
                                  std::to_string(now.size()));
    const std::vector<int> tri = cached_host_triangles(layer, layer.offset_at(time_s), roots);
    std::vector<DdmHostMap> maps(roots.size());
    bool any = false;
    for (std::size_t i = 0; i < roots.size(); ++i) {
      if (tri[i] < 0) continue;
      const glm::uvec3 t = host.triangles[static_cast<std::size_t>(tri[i])];
      const glm::dvec3 a0 = host.positions[t.x], b0 = host.positions[t.y], c0 = host.positions[t.z];
      const glm::dvec3 a1 = now[t.x], b1 = now[t.y], c1 = now[t.z];
      if (a0 == a1 && b0 == b1 && c0 == c1) continue;  // unmoved: exactly the identity
      glm::dmat3 f0, f1;
      if (!triangle_frame(a0, b0, c0, f0)) continue;
      DdmHostMap& h = maps[i];
      if (triangle_frame(a1, b1, c1, f1)) h.linear = similarity_part(f1 * glm::inverse(f0));  // else translated only
      // Anchored at the triangle's vertex nearest the root: a tile whose triangle a cut tears apart rides with the
      // side its nearest vertex is on.
      const glm::dvec3 r = roots[i].p;
      const int k = glm::length(a0 - r) <= glm::length(b0 - r) ? (glm::length(a0 - r) <= glm::length(c0 - r) ? 0 : 2)
                                                               : (glm::length(b0 - r) <= glm::length(c0 - r) ? 1 : 2);
      const glm::dvec3 v0 = k == 0 ? a0 : k == 1 ? b0 : c0, v1 = k == 0 ? a1 : k == 1 ? b1 : c1;
      h.shift = v1 - h.linear * v0;
      any = true;
    }
    if (any) hosts_ = std::move(maps);
  }

  if (!has_lattice) return;
  // 3. the lattice, and per instance the side of every break its root is on
  const glm::dvec3 inf(std::numeric_limits<double>::infinity());
  if (object.ffd) {
    lattice_ = &object.ffd->lattice;
    keep_ = object.ffd;
    embedding_ = object.ffd->embedding;
  } else {
    const std::shared_ptr<const DffdRig> rig = dffd_rig_at(object.dffd, time_s);  // a keyed seam at time_s
    lattice_ = &rig->lattice;
    keep_ = rig;
    embedding_ = object.dffd->embedding;
    identity_outside_ = object.dffd->identity_outside;
  }
  offset_ = object.offset_at(time_s);
  if (!std::isfinite(offset_.x) || !std::isfinite(offset_.y) || !std::isfinite(offset_.z))
    throw std::invalid_argument("object '" + object.name + "': parameter offset is not finite");
  if (sides) {
    lo_.assign(roots.size(), -inf);
    hi_.assign(roots.size(), inf);
    const double eps = object.dffd->eps;
    for (std::size_t i = 0; i < roots.size(); ++i) {
      glm::dvec3 x = roots[i].p;
      if (!hosts_.empty()) x = hosts_[i].linear * x + hosts_[i].shift;
      const glm::dvec3 p = embedding_.apply(glm::dvec3(model_ * glm::dvec4(x, 1.0))) + offset_;
      for (const Discontinuity& d : object.dffd->discontinuities) {
        if (p[d.axis] < d.u0)
          hi_[i][d.axis] = std::min(hi_[i][d.axis], d.u0 - eps);
        else
          lo_[i][d.axis] = std::max(lo_[i][d.axis], d.u0 + eps);
      }
    }
  }
}

TriMesh DdmLayerDeformation::apply(const TriMesh& layer_mesh) const {
  const std::size_t n = layer_mesh.positions.size();
  if (n != first_vertex_.back())
    throw std::invalid_argument("layer mesh has " + std::to_string(n) + " vertices, its instances " +
                                std::to_string(first_vertex_.back()));
  if (!layer_mesh.normals.empty() && layer_mesh.normals.size() != n)
    throw std::invalid_argument("layer mesh has " + std::to_string(layer_mesh.normals.size()) + " normals for " +
                                std::to_string(n) + " vertices");
  TriMesh out = layer_mesh;
  const bool normals = !out.normals.empty();
  const glm::dmat3 lin(model_);
  const glm::dmat3 nrm = glm::transpose(glm::inverse(lin));
  const std::size_t instances = first_vertex_.size() - 1;
  // Steps 1–2 per instance (object space → world), then the lattice's parameters.
  std::vector<glm::dvec3> params(lattice_ ? n : 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, instances, 64), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const DdmHostMap* h = hosts_.empty() ? nullptr : &hosts_[i];
      const glm::dmat3 hc = h ? cofactor(h->linear) : glm::dmat3(1.0);
      for (std::size_t v = first_vertex_[i]; v < first_vertex_[i + 1]; ++v) {
        glm::dvec3 x = out.positions[v];
        if (h) x = h->linear * x + h->shift;
        out.positions[v] = glm::dvec3(model_ * glm::dvec4(x, 1.0));
        if (normals) {
          glm::dvec3 m = nrm * (h ? hc * out.normals[v] : out.normals[v]);
          const double len = glm::length(m);
          if (len > 0.0) out.normals[v] = m / len;
        }
        if (lattice_) {
          glm::dvec3 p = embedding_.apply(out.positions[v]) + offset_;
          if (!lo_.empty()) p = glm::clamp(p, lo_[i], hi_[i]);
          params[v] = p;
        }
      }
    }
  });
  if (lattice_) {  // 3.
    std::vector<glm::dvec3> positions, mapped;
    const std::vector<glm::dvec3> rest_normals =
        normals ? out.normals : std::vector<glm::dvec3>(n, glm::dvec3(0, 0, 1));
    if (identity_outside_)
      ffd_evaluate_identity_outside(*lattice_, embedding_, params, rest_normals, positions, mapped);
    else
      ffd_evaluate(*lattice_, embedding_, params, rest_normals, positions, mapped);
    out.positions = std::move(positions);
    if (normals) out.normals = std::move(mapped);
  }
  if (flip_)
    for (auto& f : out.triangles) std::swap(f.y, f.z);
  return out;
}

DdmFastFollower::DdmFastFollower() = default;
DdmFastFollower::~DdmFastFollower() = default;

void DdmFastFollower::bind(const SceneObject& object, const TriMesh& layer_mesh) {
  if (!object.ffd) throw std::invalid_argument("object '" + object.name + "' has no FFD lattice");
  if (object.dffd || object.clip || object.morph)
    throw std::invalid_argument("object '" + object.name + "': host maps or DFFD sides need the reference path");
  if (layer_mesh.normals.size() != layer_mesh.positions.size())
    throw std::invalid_argument("layer mesh has " + std::to_string(layer_mesh.normals.size()) + " normals for " +
                                std::to_string(layer_mesh.positions.size()) + " vertices");
  const TriMesh world = transformed(layer_mesh, object.transform);
  ffd_ = std::make_unique<FfdFastEvaluator>();
  ffd_->set_lattice(object.ffd->lattice, object.ffd->embedding);
  ffd_->bind_vertices(embed_points(object.ffd->embedding, world.positions), world.normals);
}

void DdmFastFollower::evaluate(const glm::dvec3& offset, std::vector<glm::vec3>& positions,
                               std::vector<glm::vec3>& normals) {
  if (!ffd_) throw std::invalid_argument("DdmFastFollower: nothing bound");
  ffd_->evaluate(offset);
  ffd_->read_results_float(positions, normals);
}

std::size_t DdmFastFollower::vertex_count() const { return ffd_ ? ffd_->vertex_count() : 0; }

TriMesh ddm_layer_world_mesh(const SceneObject& object, const DdmLayer& layer, const TriMesh& layer_mesh,
                             double time_s) {
  const DdmLayerDeformation d(object, layer, time_s);
  if (d.rigid()) return transformed(layer_mesh, object.transform);  // as before: bit for bit
  return d.apply(layer_mesh);
}

}  // namespace trispline::core
