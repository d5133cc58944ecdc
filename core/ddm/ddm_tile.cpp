// DDM tiles: generated tiles (thorn, flower, chain, hex, hair), canonical tiles from meshes, topology check. See
// ddm_tile.h. Source: seed ch. 5 §5.2 (canonical tile space), Eq. 5.3 / Fig. 5.8 (metamorphosis needs equal topology).
#include "core/ddm/ddm_tile.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>

#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A closed tube-like grid: `rings` rings of `segments` points (ring 0 at the foot), a foot centre below ring 0 and
// a tip above the last ring; triangles wound outward (counter-clockwise seen from outside).
TriMesh ring_grid(int rings, int segments, const std::function<glm::dvec3(int, int)>& ring_point,
                  const glm::dvec3& foot, const glm::dvec3& tip) {
  TriMesh m;
  for (int k = 0; k < rings; ++k)
    for (int s = 0; s < segments; ++s) m.positions.push_back(ring_point(k, s));
  const auto foot_i = static_cast<unsigned>(m.positions.size());
  m.positions.push_back(foot);
  const auto tip_i = foot_i + 1;
  m.positions.push_back(tip);
  auto at = [&](int k, int s) { return static_cast<unsigned>(k * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) m.triangles.emplace_back(foot_i, at(0, s + 1), at(0, s));  // faces −w
  for (int k = 0; k + 1 < rings; ++k)
    for (int s = 0; s < segments; ++s) {
      m.triangles.emplace_back(at(k, s), at(k, s + 1), at(k + 1, s + 1));
      m.triangles.emplace_back(at(k, s), at(k + 1, s + 1), at(k + 1, s));
    }
  for (int s = 0; s < segments; ++s) m.triangles.emplace_back(at(rings - 1, s), at(rings - 1, s + 1), tip_i);
  compute_vertex_normals(m);
  return m;
}

constexpr int kThornRings = 26, kThornSegments = 24;

TriMesh thorn_mesh() {
  const auto ring = [](int k, int s) {
    const double t = double(k) / kThornRings, a = 2.0 * kPi * s / kThornSegments;
    const double r = 0.3 * std::pow(1.0 - t, 1.3), cx = 0.5 + 0.18 * t * t;  // a horn bending towards +x
    return glm::dvec3(cx + r * std::cos(a), 0.5 + r * std::sin(a), 0.9 * t);
  };
  return ring_grid(kThornRings, kThornSegments, ring, {0.5, 0.5, 0.0}, {0.68, 0.5, 0.9});
}

TriMesh flower_mesh() {  // the thorn's grid: a stem (rings 0–12), then a cup of five petals (rings 13–25)
  const auto ring = [](int k, int s) {
    const double a = 2.0 * kPi * s / kThornSegments;
    if (k <= 12) {
      const double t = k / 12.0;
      return glm::dvec3(0.5 + 0.05 * std::cos(a), 0.5 + 0.05 * std::sin(a), 0.45 * t);
    }
    const double tau = (k - 12) / double(kThornRings - 13);  // (0, 1]
    const double petal = 0.62 + 0.38 * std::cos(5.0 * a);
    const double r = 0.05 + 0.4 * tau * petal;
    return glm::dvec3(0.5 + r * std::cos(a), 0.5 + r * std::sin(a), 0.45 + 0.16 * std::sin(0.5 * kPi * tau));
  };
  return ring_grid(kThornRings, kThornSegments, ring, {0.5, 0.5, 0.0}, {0.5, 0.5, 0.58});
}

// A stadium-shaped torus: centre line of two half circles of radius `bend` joined by straight parts from
// centre − half_len to centre + half_len along `along`; `across` is the other in-plane direction; tube radius `tube`.
void append_link(TriMesh& m, const glm::dvec3& centre, const glm::dvec3& along, const glm::dvec3& across,
                 double half_len, double bend, double tube) {
  constexpr int kLine = 48, kTube = 12;
  const glm::dvec3 normal = glm::normalize(glm::cross(along, across));
  const double straight = 2.0 * half_len, arc = kPi * bend, total = 2.0 * (straight + arc);
  const auto base = static_cast<unsigned>(m.positions.size());
  for (int i = 0; i < kLine; ++i) {
    double d = total * i / kLine;  // arc length along the centre line
    glm::dvec3 c, radial;          // centre-line point and its in-plane outward direction
    if (d < straight) {
      c = centre + (d - half_len) * along - bend * across, radial = -across;
    } else if ((d -= straight) < arc) {
      const double a = d / bend - 0.5 * kPi;
      radial = std::cos(a) * along + std::sin(a) * across;
      c = centre + half_len * along + bend * radial;
    } else if ((d -= arc) < straight) {
      c = centre + (half_len - d) * along + bend * across, radial = across;
    } else {
      d -= straight;
      const double a = d / bend + 0.5 * kPi;
      radial = std::cos(a) * along + std::sin(a) * across;
      c = centre - half_len * along + bend * radial;
    }
    for (int j = 0; j < kTube; ++j) {
      const double b = 2.0 * kPi * j / kTube;
      const glm::dvec3 n = std::cos(b) * radial + std::sin(b) * normal;
      m.positions.push_back(c + tube * n);
      m.normals.push_back(n);
    }
  }
  auto at = [&](int i, int j) { return base + static_cast<unsigned>((i % kLine) * kTube + (j % kTube)); };
  for (int i = 0; i < kLine; ++i)
    for (int j = 0; j < kTube; ++j) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
}

TriMesh chain_mesh() {
  TriMesh m;
  // Lying link (in the x–y plane) and standing link (in the x–w plane); each passes through the other's hole.
  append_link(m, {0.35, 0.5, 0.22}, {1, 0, 0}, {0, 1, 0}, 0.13, 0.1, 0.05);
  append_link(m, {0.7, 0.5, 0.22}, {1, 0, 0}, {0, 0, 1}, 0.1, 0.14, 0.05);
  return m;
}

TriMesh hex_mesh() {
  constexpr double kInset = 0.03, kHeight = 0.15;  // a gap between neighbours, the slab's thickness
  const glm::dvec2 corner[6] = {{0.5, 0.0}, {1.0, 0.25}, {1.0, 0.75}, {0.5, 1.0}, {0.0, 0.75}, {0.0, 0.25}};
  glm::dvec2 c[6];
  for (int i = 0; i < 6; ++i) c[i] = glm::dvec2(0.5) + (1.0 - kInset) * (corner[i] - glm::dvec2(0.5));
  TriMesh m;
  auto add = [&](const glm::dvec3& p, const glm::dvec3& n) {
    m.positions.push_back(p), m.normals.push_back(n);
    return static_cast<unsigned>(m.positions.size() - 1);
  };
  for (int cap = 0; cap < 2; ++cap) {  // flat top (+w) and bottom (−w), fans from the centre
    const double w = cap == 0 ? kHeight : 0.0;
    const glm::dvec3 n(0.0, 0.0, cap == 0 ? 1.0 : -1.0);
    const unsigned centre = add({0.5, 0.5, w}, n);
    unsigned ring[6];
    for (int i = 0; i < 6; ++i) ring[i] = add({c[i].x, c[i].y, w}, n);
    for (int i = 0; i < 6; ++i)
      cap == 0 ? m.triangles.emplace_back(centre, ring[i], ring[(i + 1) % 6])
               : m.triangles.emplace_back(centre, ring[(i + 1) % 6], ring[i]);
  }
  for (int i = 0; i < 6; ++i) {  // sides, one flat quad each (corners listed counter-clockwise seen from +w)
    const glm::dvec2 a = c[i], b = c[(i + 1) % 6];
    const glm::dvec3 n = glm::normalize(glm::dvec3(b.y - a.y, a.x - b.x, 0.0));
    const unsigned p0 = add({a.x, a.y, 0.0}, n), p1 = add({b.x, b.y, 0.0}, n), p2 = add({b.x, b.y, kHeight}, n),
                   p3 = add({a.x, a.y, kHeight}, n);
    m.triangles.emplace_back(p0, p1, p2);
    m.triangles.emplace_back(p0, p2, p3);
  }
  return m;
}

// A tuft of hair (seed Fig. 5.10, Table 5.1's horse): kHairStrands thin closed tubes rooted at jittered points of a
// 6 × 6 grid in the cell, each kHairRings rings of kHairSegments points tapering to its tip, leaning and curling
// towards +x by its own amount, 0.55–0.95 tile units long. The jitter is a fixed hash of the strand index, so the tile
// is the same bit for bit everywhere.
constexpr int kHairStrands = 32, kHairRings = 8, kHairSegments = 4;

double hair_hash(unsigned i, unsigned salt) {  // [0, 1), SplitMix64's finaliser
  std::uint64_t z = (std::uint64_t(i) << 8 | salt) + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return double((z ^ (z >> 31)) >> 11) / double(std::uint64_t{1} << 53);
}

TriMesh hair_mesh() {
  TriMesh m;
  for (unsigned i = 0; i < unsigned(kHairStrands); ++i) {
    const unsigned cell = i % 36;
    const glm::dvec2 root(0.14 + 0.12 * (cell % 6) + 0.08 * (hair_hash(i, 1) - 0.5),
                          0.2 + 0.12 * (cell / 6) + 0.08 * (hair_hash(i, 2) - 0.5));
    const double length = 0.55 + 0.4 * hair_hash(i, 3), lean = 0.1 + 0.15 * hair_hash(i, 4);
    const double side = 0.08 * (hair_hash(i, 5) - 0.5), radius = 0.012;
    const auto centre = [&](double t) {  // the strand's centre line: up, leaning (more towards the tip) to +x
      return glm::dvec3(root.x + lean * t * t, root.y + side * t, length * t);
    };
    const auto ring = [&](int k, int seg) {
      const double t = double(k) / kHairRings, a = 2.0 * kPi * seg / kHairSegments;
      const double r = radius * (1.0 - 0.85 * t);
      return centre(t) + r * glm::dvec3(std::cos(a), std::sin(a), 0.0);
    };
    TriMesh strand = ring_grid(kHairRings, kHairSegments, ring, centre(0.0), centre(1.0));
    const auto base = static_cast<unsigned>(m.positions.size());
    m.positions.insert(m.positions.end(), strand.positions.begin(), strand.positions.end());
    m.normals.insert(m.normals.end(), strand.normals.begin(), strand.normals.end());
    for (const glm::uvec3& t : strand.triangles) m.triangles.push_back(t + glm::uvec3(base));
  }
  return m;
}

}  // namespace

bool is_generated_ddm_tile(const std::string& kind) {
  return kind == "thorn" || kind == "flower" || kind == "chain" || kind == "hex" || kind == "hair";
}

DdmTile make_ddm_tile(const std::string& kind) {
  if (kind == "thorn") return {kind, thorn_mesh()};
  if (kind == "flower") return {kind, flower_mesh()};
  if (kind == "chain") return {kind, chain_mesh()};
  if (kind == "hex") return {kind, hex_mesh()};
  if (kind == "hair") return {kind, hair_mesh()};
  throw std::invalid_argument("tile: unknown generated tile '" + kind +
                              "' (thorn, flower, chain, hex, hair, or a mesh file)");
}

DdmTileMaterials ddm_tile_materials(const std::vector<DdmTile>& tiles, const glm::dvec3& untextured_color) {
  DdmTileMaterials out;
  out.first_slot.assign(tiles.size(), 0);
  const MaterialSet* shared = nullptr;
  bool any = false, one_set = true;
  for (const DdmTile& t : tiles) {
    if (t.materials && !t.materials->empty()) any = true;
    if (!t.materials || t.materials->empty() || (shared && shared != t.materials.get())) one_set = false;
    if (t.materials) shared = t.materials.get();
  }
  if (!any) return out;
  if (one_set) {
    out.set = tiles.front().materials;
    return out;
  }
  auto set = std::make_shared<MaterialSet>();
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    out.first_slot[i] = static_cast<MaterialSlot>(set->materials.size());
    const std::shared_ptr<const MaterialSet>& own = tiles[i].materials;
    if (!own || own->empty()) {
      Material m;  // as the tile looks in an untextured layer: its colour, metallic 0, roughness 0.6 (gltf_io.h)
      m.name = tiles[i].name;
      m.base_color = glm::dvec4(untextured_color, 1.0);
      m.metallic = 0.0;
      m.roughness = 0.6;
      set->materials.push_back(m);
      continue;
    }
    const int image_base = static_cast<int>(set->images.size());
    set->images.insert(set->images.end(), own->images.begin(), own->images.end());
    for (Material m : own->materials) {
      for (MaterialTexture* t : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                                 &m.occlusion_texture, &m.emissive_texture})
        if (t->present()) t->image += image_base;
      set->materials.push_back(std::move(m));
    }
    if (set->materials.size() > kMaxMaterialsPerMesh)
      throw std::invalid_argument("tiles: more than " + std::to_string(kMaxMaterialsPerMesh) + " materials");
  }
  out.set = std::move(set);
  return out;
}

DdmTileFrame canonical_ddm_tile_frame(const TriMesh& mesh, const std::string& name) {
  if (mesh.triangles.empty()) throw std::invalid_argument("tile: '" + name + "' has no triangles");
  Aabb box;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::dvec3& p = mesh.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("tile: '" + name + "' has a non-finite position at vertex " + std::to_string(v));
    box.extend(p);
  }
  for (const glm::uvec3& t : mesh.triangles)
    if (t.x >= mesh.positions.size() || t.y >= mesh.positions.size() || t.z >= mesh.positions.size())
      throw std::invalid_argument("tile: '" + name + "' has a triangle index ≥ #V");
  const glm::dvec3 ext = box.size();
  if (!(ext.x > 0.0) || !(ext.y > 0.0))
    throw std::invalid_argument("tile: '" + name + "' is flat across (zero x or y extent): nothing to lay out");
  return {box.lo, glm::dvec3(1.0 / ext.x, 1.0 / ext.y, 1.0 / std::max(ext.x, ext.y))};
}

DdmTile canonical_ddm_tile(const TriMesh& mesh, const std::string& name, std::shared_ptr<const MaterialSet> materials) {
  const DdmTileFrame frame = canonical_ddm_tile_frame(mesh, name);
  const glm::dvec3 &lo = frame.lo, &scale = frame.scale;
  DdmTile tile{name, mesh, nullptr};
  if (materials && !materials->empty()) {
    tile.materials = std::move(materials);
    if (tile.mesh.face_material.size() != tile.mesh.triangle_count())
      tile.mesh.face_material.assign(tile.mesh.triangle_count(), kMaterialSurface);
    if (tile.mesh.uvs.size() != tile.mesh.vertex_count()) {  // a planar projection from above: (x, y) of the tile
      tile.mesh.uvs.resize(tile.mesh.vertex_count());
      for (std::size_t v = 0; v < tile.mesh.vertex_count(); ++v)
        tile.mesh.uvs[v] = (glm::dvec2(mesh.positions[v]) - glm::dvec2(lo)) * glm::dvec2(scale);
    }
  } else {
    tile.mesh.uvs.clear();
    tile.mesh.face_material.clear();
  }
  for (glm::dvec3& p : tile.mesh.positions) p = (p - lo) * scale;
  if (tile.mesh.normals.size() == tile.mesh.positions.size()) {
    for (glm::dvec3& n : tile.mesh.normals) {  // inverse transpose of diag(scale) = diag(1 / scale)
      const glm::dvec3 q = n / scale;
      const double len = glm::length(q);
      if (len > 0.0 && std::isfinite(len)) n = q / len;
    }
  } else {
    compute_vertex_normals(tile.mesh);
  }
  return tile;
}

void require_same_ddm_topology(const DdmTile& a, const DdmTile& b) {
  if (a.mesh.vertex_count() != b.mesh.vertex_count())
    throw std::invalid_argument("tile: '" + a.name + "' has " + std::to_string(a.mesh.vertex_count()) +
                                " vertices and '" + b.name + "' " + std::to_string(b.mesh.vertex_count()) +
                                ": a metamorphosis needs tiles of the same topology");
  if (a.mesh.triangles.size() != b.mesh.triangles.size())
    throw std::invalid_argument("tile: '" + a.name + "' and '" + b.name +
                                "' have different triangle counts: a metamorphosis needs the same topology");
  for (std::size_t f = 0; f < a.mesh.triangles.size(); ++f)
    if (a.mesh.triangles[f] != b.mesh.triangles[f])
      throw std::invalid_argument("tile: '" + a.name + "' and '" + b.name + "' differ at triangle " +
                                  std::to_string(f) + ": a metamorphosis needs the same topology");
}

glm::dvec3 ddm_tile_up(const glm::dvec3& p, int up_axis) {
  if (up_axis == 1) return {p.z, p.x, p.y};
  if (up_axis == 0) return {p.y, p.z, p.x};
  return p;
}

void ddm_tile_up(TriMesh& mesh, int up_axis) {
  for (glm::dvec3& p : mesh.positions) p = ddm_tile_up(p, up_axis);
  for (glm::dvec3& n : mesh.normals) n = ddm_tile_up(n, up_axis);
}

DdmTile DdmTileClip::pose(const DdmTile& rest, double time_s) const {
  if (!clip) return rest;
  if (clip->vertex_count() != rest.mesh.vertex_count())
    throw std::invalid_argument("tile '" + rest.name + "': its clip '" + clip->name() + "' moves " +
                                std::to_string(clip->vertex_count()) + " vertices, the tile has " +
                                std::to_string(rest.mesh.vertex_count()));
  std::vector<glm::dvec3> positions, normals;
  clip->pose(wrap_clip_time(time_s, 0.0, 1.0, clip->duration_s(), true), positions, normals);
  DdmTile out = rest;
  out.mesh.normals.resize(out.mesh.vertex_count());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const glm::dvec3 p = (ddm_tile_up(positions[v], up_axis) - frame.lo) * frame.scale;
    const glm::dvec3 q = ddm_tile_up(normals[v], up_axis) / frame.scale;  // inverse transpose of diag(scale)
    const double len = glm::length(q);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !(len > 0.0) || !std::isfinite(len))
      throw std::invalid_argument("tile '" + rest.name + "': its clip's pose at " + std::to_string(time_s) +
                                  " s is not finite at vertex " + std::to_string(v));
    out.mesh.positions[v] = p;
    out.mesh.normals[v] = q / len;
  }
  return out;
}

}  // namespace trispline::core
