// DdmGl: live DDM layers drawn and captured through shaders/ddm.vert.glsl. See ddm_gl.h; seed §5.3.2.
#include "gpu/eval/ddm_gl.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/mesh/mesh_decimate.h"
#include "gpu/eval/ffd_gl_lattice.h"

namespace trispline::gpu {
namespace {

constexpr GLuint kMapsBinding = 6;  // SSBO binding of the maps (FFD uses 0–5)

// One instance as the vertex shader reads it (attributes 4, 5, 6 with divisor 1).
struct InstanceRecord {
  GLint slot;
  float origin[2];
  float size[2];
};
static_assert(sizeof(InstanceRecord) == 20);

// One instance's follow data as the FOLLOW variant reads it (attributes 7–12 with divisor 1): host map columns and
// shift, parameter box.
struct FollowRecord {
  float c0[3], c1[3], c2[3], shift[3], lo[3], hi[3];
};
static_assert(sizeof(FollowRecord) == 72);

void put3(float* dst, const glm::dvec3& v) {
  for (int i = 0; i < 3; ++i) dst[i] = static_cast<float>(v[i]);
}

std::vector<float> to_float(const std::vector<glm::dvec3>& v) {
  std::vector<float> out(3 * v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    out[3 * i] = static_cast<float>(v[i].x);
    out[3 * i + 1] = static_cast<float>(v[i].y);
    out[3 * i + 2] = static_cast<float>(v[i].z);
  }
  return out;
}

Buffer upload_array(GLenum target, const void* data, std::size_t bytes) {
  Buffer b = Buffer::create();
  glBindBuffer(target, b.id());
  glBufferData(target, GLsizeiptr(bytes), data, GL_STATIC_DRAW);
  glBindBuffer(target, 0);
  return b;
}

std::invalid_argument layer_error(const core::DdmLayer& layer, const std::string& what) {
  return std::invalid_argument("layer '" + layer.name + "': " + what);
}

}  // namespace

DdmPose DdmPose::at(const core::DdmLayer& layer, double time_s) {
  return {layer.morph_tiles.empty() ? 0.0 : layer.alpha_at(time_s), layer.offset_at(time_s), layer.transform_at(time_s),
          layer.height_at(time_s), time_s};
}

struct DdmGl::MapsGl {
  std::shared_ptr<const core::DdmMaps> maps;  // held so the address cannot be reused
  Buffer samples;                             // #slots × R_v × R_u × 18 floats
};

namespace {
// A tile's buffers: positions, normals, its partner's (the tile's own without one), indices.
struct TileBuffers {
  GLuint positions, normals, morph_positions, morph_normals, indices;
  GLuint uvs = 0;  // 0: the tile has no texture coordinates (attribute 13 unused)
};

// The tile's vertex attributes 0–3 and index buffer, and the per-instance attributes 4–6 from `instances`, recorded in
// `vao`.
void record_tile_vao(const TileBuffers& tile, GLuint vao, GLuint instances) {
  glBindVertexArray(vao);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, tile.indices);
  float_attribute(0, tile.positions, 3);
  float_attribute(1, tile.normals, 3);
  float_attribute(2, tile.morph_positions, 3);
  float_attribute(3, tile.morph_normals, 3);
  if (tile.uvs) {
    float_attribute(13, tile.uvs, 2);
  }
  glBindBuffer(GL_ARRAY_BUFFER, instances);
  const GLsizei stride = sizeof(InstanceRecord);
  glEnableVertexAttribArray(4);
  glVertexAttribIPointer(4, 1, GL_INT, stride, reinterpret_cast<const void*>(offsetof(InstanceRecord, slot)));
  glEnableVertexAttribArray(5);
  glVertexAttribPointer(5, 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offsetof(InstanceRecord, origin)));
  glEnableVertexAttribArray(6);
  glVertexAttribPointer(6, 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offsetof(InstanceRecord, size)));
  for (GLuint a = 4; a <= 6; ++a) glVertexAttribDivisor(a, 1);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}
}  // namespace

struct DdmGl::LayerGl {
  // One tile mesh of the layer and the instances that use it (a contiguous run of the instance buffer).
  struct TileGl {
    // A run of the tile's indices drawn with one material (texture-mapped tiles; one run of slot 0 otherwise).
    struct SlotRange {
      core::MaterialSlot slot;
      GLsizei first, count;  // indices
    };
    Buffer positions, normals, morph_positions, morph_normals, indices, uvs;
    std::vector<SlotRange> ranges;  // the index buffer grouped by the layer's material slot
    VertexArray vao;
    VertexArray selected_vao;  // the same attributes with the instances from `selected` (made at first use)
    GLsizei vertex_count = 0, index_count = 0;
    GLuint first_instance = 0;
    GLsizei instance_count = 0;
    // Levels of detail (kDdmLodLevels; `levels` of them present): each a run of the index buffer after the full
    // list (level 0 = [0, index_count)) and the vertices it uses.
    int levels = 1;
    GLsizei level_first[kDdmLodLevels] = {}, level_count[kDdmLodLevels] = {};
    std::size_t level_vertices[kDdmLodLevels] = {};
    GLuint selected_first[kDdmLodLevels] = {};  // the tile's runs in `selected`, one per level
    GLsizei selected_count[kDdmLodLevels] = {};
  };
  std::shared_ptr<const core::DdmLayer> layer;         // held so the address cannot be reused
  std::shared_ptr<const core::MaterialSet> materials;  // core::ddm_tile_materials(layer.tiles, ...).set, or null
  glm::dvec3 materials_color{1.0};                     // the untextured tiles' colour in `materials`
  Buffer instances;                                    // InstanceRecord per instance, grouped by tile (stable)
  std::vector<InstanceRecord> records;                 // its contents (the source of `selected`)
  std::vector<TileGl> tiles;                           // per layer tile
  std::vector<std::size_t> grouped;                    // position in the instance buffer → index in layer.instances
  std::size_t vertices = 0;                            // Σ instances × tile vertices
  Buffer follow;                              // FollowRecord per instance (grouped order), when drawn following
  std::vector<FollowRecord> follow_uploaded;  // what `follow` holds
  Buffer selected;                            // the instances of the last DdmSelection, grouped by tile
  std::uint64_t selected_version = 0;         // its version (0: none uploaded yet)
  std::size_t selected_vertices = 0;
  bool levels_made = false;  // ensure_levels ran (the tiles' `levels` are final)
  // An articulated tile (core::DdmLayer::tile_clip): the scene time its buffers are posed at (NaN: the rest pose).
  double posed_time = std::numeric_limits<double>::quiet_NaN();

  // Without a partner the tile itself (drawn with α = 0, so V = V1 exactly).
  static TileBuffers buffers(const TileGl& t) {
    return {t.positions.id(),
            t.normals.id(),
            t.morph_positions ? t.morph_positions.id() : t.positions.id(),
            t.morph_normals ? t.morph_normals.id() : t.normals.id(),
            t.indices.id(),
            t.uvs ? t.uvs.id() : 0};
  }
};

DdmGl::DdmGl(std::shared_ptr<FfdProgramCache> programs)
    : programs_(programs ? std::move(programs) : std::make_shared<FfdProgramCache>()) {}

DdmGl::~DdmGl() = default;

const ShaderProgram& DdmGl::program(const ShaderDefines& variant) {
  return programs_->get({"ddm.vert.glsl", "mesh.frag.glsl"}, variant);
}

std::size_t DdmGl::cached_layers() const { return layers_.size(); }
std::size_t DdmGl::cached_maps() const { return maps_.size(); }

void DdmGl::check(const core::DdmLayer& layer) {
  if (!layer.maps) throw layer_error(layer, "no maps");
  const core::DdmMaps& m = *layer.maps;
  if (m.resolution.x < 2 || m.resolution.y < 2) throw layer_error(layer, "map resolution below 2");
  if (m.samples.size() != std::size_t(m.slot_count()) * m.samples_per_slot() * core::DdmMaps::kFloatsPerSample)
    throw layer_error(layer, "maps hold " + std::to_string(m.samples.size()) + " floats, not #slots × R_u × R_v × 18");
  if (!std::isfinite(layer.height) || !(layer.height > 0.0)) throw layer_error(layer, "height must be finite and > 0");
  if (layer.tiles.empty()) throw layer_error(layer, "no tiles");
  for (const core::DdmTile& t : layer.tiles)
    if (t.mesh.normals.size() != t.mesh.vertex_count())
      throw layer_error(layer, "tile '" + t.name + "' has no per-vertex normals");
  if (!layer.morph_tiles.empty()) {
    if (layer.morph_tiles.size() != layer.tiles.size()) throw layer_error(layer, "morph tiles: need one per tile");
    for (std::size_t i = 0; i < layer.tiles.size(); ++i) {
      const core::TriMesh &a = layer.tiles[i].mesh, &b = layer.morph_tiles[i].mesh;
      if (a.vertex_count() != b.vertex_count() || a.triangle_count() != b.triangle_count() ||
          b.normals.size() != b.vertex_count())
        throw layer_error(
            layer, "morph tile '" + layer.morph_tiles[i].name + "' does not match tile '" + layer.tiles[i].name + "'");
    }
  }
  for (std::size_t k = 0; k < layer.instances.size(); ++k) {
    const core::DdmInstance& inst = layer.instances[k];
    if (inst.tile < 0 || inst.tile >= int(layer.tiles.size()))
      throw layer_error(layer, "instance " + std::to_string(k) + " uses tile " + std::to_string(inst.tile));
    if (inst.chart < 0 || inst.chart >= int(m.slot_of_chart.size()) || m.slot_of_chart[std::size_t(inst.chart)] < 0 ||
        m.slot_of_chart[std::size_t(inst.chart)] >= m.slot_count())
      throw layer_error(layer, "instance " + std::to_string(k) + " is on chart " + std::to_string(inst.chart) +
                                   ", which the maps do not hold");
  }
}

DdmGl::MapsGl& DdmGl::maps_for(const std::shared_ptr<const core::DdmMaps>& maps) {
  auto [it, inserted] = maps_.try_emplace(maps.get());
  if (inserted) {
    auto m = std::make_unique<MapsGl>();
    m->maps = maps;
    // An empty SSBO cannot be bound; keep at least one float.
    const std::size_t bytes = std::max<std::size_t>(maps->samples.size(), 1) * sizeof(float);
    m->samples = upload_array(GL_SHADER_STORAGE_BUFFER, maps->samples.empty() ? nullptr : maps->samples.data(), bytes);
    it->second = std::move(m);
    ++uploads_;
    check_gl_error("DdmGl: maps upload");
  }
  return *it->second;
}

DdmGl::LayerGl& DdmGl::layer_for(const std::shared_ptr<const core::DdmLayer>& layer) {
  if (auto it = layers_.find(layer.get()); it != layers_.end()) return *it->second;
  check(*layer);
  // No vertex array bound while uploading: binding GL_ELEMENT_ARRAY_BUFFER would change the bound VAO's indices.
  glBindVertexArray(0);
  const core::DdmLayer& l = *layer;
  auto g = std::make_unique<LayerGl>();
  g->layer = layer;
  const core::DdmTileMaterials materials = core::ddm_tile_materials(l.tiles);
  g->materials = materials.set;
  // Instances grouped by tile, in layer order within a group (so each tile's run is one instanced draw).
  std::vector<InstanceRecord> records;
  records.reserve(l.instances.size());
  g->tiles.resize(l.tiles.size());
  for (std::size_t t = 0; t < l.tiles.size(); ++t) {
    LayerGl::TileGl& tile = g->tiles[t];
    tile.first_instance = GLuint(records.size());
    for (std::size_t k = 0; k < l.instances.size(); ++k) {
      const core::DdmInstance& inst = l.instances[k];
      if (inst.tile != int(t)) continue;
      records.push_back({l.maps->slot_of_chart[std::size_t(inst.chart)],
                         {float(inst.origin.x), float(inst.origin.y)},
                         {float(inst.size.x), float(inst.size.y)}});
      g->grouped.push_back(k);
    }
    tile.instance_count = GLsizei(records.size() - tile.first_instance);
  }
  g->instances = upload_array(GL_ARRAY_BUFFER, records.empty() ? nullptr : records.data(),
                              std::max<std::size_t>(records.size(), 1) * sizeof(InstanceRecord));
  for (std::size_t t = 0; t < l.tiles.size(); ++t) {
    LayerGl::TileGl& tile = g->tiles[t];
    const core::TriMesh& mesh = l.tiles[t].mesh;
    tile.vertex_count = GLsizei(mesh.vertex_count());
    tile.index_count = GLsizei(3 * mesh.triangle_count());
    g->vertices += std::size_t(tile.vertex_count) * std::size_t(tile.instance_count);
    if (tile.instance_count == 0) continue;  // nothing to draw: upload nothing
    const std::vector<float> p = to_float(mesh.positions), n = to_float(mesh.normals);
    tile.positions = upload_array(GL_ARRAY_BUFFER, p.data(), p.size() * sizeof(float));
    tile.normals = upload_array(GL_ARRAY_BUFFER, n.data(), n.size() * sizeof(float));
    if (!l.morph_tiles.empty()) {
      const core::TriMesh& morph = l.morph_tiles[t].mesh;
      const std::vector<float> mp = to_float(morph.positions), mn = to_float(morph.normals);
      tile.morph_positions = upload_array(GL_ARRAY_BUFFER, mp.data(), mp.size() * sizeof(float));
      tile.morph_normals = upload_array(GL_ARRAY_BUFFER, mn.data(), mn.size() * sizeof(float));
    }
    // Triangles grouped by the layer's material slot (stable; one group without materials), uvs beside.
    std::vector<std::pair<core::MaterialSlot, std::uint32_t>> order(mesh.triangle_count());
    const std::size_t own = l.tiles[t].materials ? l.tiles[t].materials->materials.size() : 0;
    for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
      const core::MaterialSlot local = f < mesh.face_material.size() ? mesh.face_material[f] : core::kMaterialSurface;
      const core::MaterialSlot slot = !g->materials || local == core::kMaterialInside
                                          ? (g->materials ? local : core::kMaterialSurface)
                                          : core::MaterialSlot(materials.first_slot[t] + (local < own ? local : 0));
      order[f] = {slot, std::uint32_t(f)};
    }
    std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::uint32_t> idx(3 * mesh.triangle_count());
    for (std::size_t i = 0; i < order.size(); ++i) {
      for (int c = 0; c < 3; ++c) idx[3 * i + std::size_t(c)] = mesh.triangles[order[i].second][c];
      if (tile.ranges.empty() || tile.ranges.back().slot != order[i].first)
        tile.ranges.push_back({order[i].first, GLsizei(3 * i), 0});
      tile.ranges.back().count += 3;
    }
    tile.level_count[0] = tile.index_count;
    tile.level_vertices[0] = std::size_t(tile.vertex_count);
    if (g->materials) {
      std::vector<float> uv(2 * mesh.vertex_count());
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        const glm::dvec2 q = mesh.uvs.size() == mesh.vertex_count() ? mesh.uvs[v] : glm::dvec2(mesh.positions[v]);
        uv[2 * v] = float(q.x), uv[2 * v + 1] = float(q.y);
      }
      tile.uvs = upload_array(GL_ARRAY_BUFFER, uv.data(), std::max<std::size_t>(uv.size(), 1) * sizeof(float));
    }
    // Uploaded through GL_ARRAY_BUFFER (no vertex array's index binding touched), then recorded in the tile's VAO.
    tile.indices = upload_array(GL_ARRAY_BUFFER, idx.empty() ? nullptr : idx.data(),
                                std::max<std::size_t>(idx.size(), 1) * sizeof(std::uint32_t));
    tile.vao = VertexArray::create();
    record_tile_vao(LayerGl::buffers(tile), tile.vao.id(), g->instances.id());
  }
  g->records = std::move(records);
  ++uploads_;
  check_gl_error("DdmGl: layer upload");
  return *layers_.emplace(layer.get(), std::move(g)).first->second;
}

void DdmGl::pose_tiles(LayerGl& g, const core::DdmLayer& layer, double time_s) {
  if (!layer.tile_clip || g.tiles.empty() || g.tiles[0].instance_count == 0 || g.posed_time == time_s) return;
  const core::DdmTile posed = layer.tile_clip->pose(layer.tiles[0], time_s);
  const std::vector<float> p = to_float(posed.mesh.positions), n = to_float(posed.mesh.normals);
  glBindBuffer(GL_ARRAY_BUFFER, g.tiles[0].positions.id());
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(p.size() * sizeof(float)), p.data());
  glBindBuffer(GL_ARRAY_BUFFER, g.tiles[0].normals.id());
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(n.size() * sizeof(float)), n.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  g.posed_time = time_s;
}

void DdmGl::set_uniforms(const ShaderProgram& p, const core::DdmLayer& layer, const DdmPose& pose,
                         const glm::dmat4& model) const {
  const core::DdmMaps& m = *layer.maps;
  glUniform2i(p.uniform("u_resolution"), m.resolution.x, m.resolution.y);
  glUniform2i(p.uniform("u_periodic"), m.periodic.x ? 1 : 0, m.periodic.y ? 1 : 0);
  p.set("u_height", float(pose.height));
  const glm::mat2 linear(pose.transform.linear());
  glUniformMatrix2fv(p.uniform("u_tile_linear"), 1, GL_FALSE, glm::value_ptr(linear));
  p.set("u_tile_shift", glm::vec2(pose.transform.shift));
  // Reduced modulo 1 in double on periodic axes (the shader wraps anyway): keeps float precision for long animations.
  glm::dvec2 offset = pose.offset;
  if (m.periodic.x) offset.x -= std::floor(offset.x);
  if (m.periodic.y) offset.y -= std::floor(offset.y);
  p.set("u_offset", glm::vec2(offset));
  p.set("u_alpha", layer.morph_tiles.empty() ? 0.0f : float(pose.alpha));
  p.set("u_model", glm::mat4(model));
  p.set("u_normal_matrix", glm::mat3(glm::inverseTranspose(glm::dmat3(model))));
}

void DdmGl::bind_follow(LayerGl& g, const ShaderProgram& p, const DdmFollow& follow) {
  const core::DdmLayerDeformation& d = *follow.deformation;
  const glm::dvec3 inf(std::numeric_limits<double>::infinity());
  std::vector<FollowRecord> records(g.grouped.size());
  for (std::size_t r = 0; r < g.grouped.size(); ++r) {
    const std::size_t k = g.grouped[r];
    const core::DdmHostMap h = d.hosts().empty() ? core::DdmHostMap{} : d.hosts()[k];
    FollowRecord& f = records[r];
    put3(f.c0, h.linear[0]), put3(f.c1, h.linear[1]), put3(f.c2, h.linear[2]), put3(f.shift, h.shift);
    put3(f.lo, d.param_lo().empty() ? -inf : d.param_lo()[k]);
    put3(f.hi, d.param_hi().empty() ? inf : d.param_hi()[k]);
  }
  const bool same = records.size() == g.follow_uploaded.size() &&
                    std::equal(records.begin(), records.end(), g.follow_uploaded.begin(),
                               [](const FollowRecord& a, const FollowRecord& b) {
                                 return std::memcmp(&a, &b, sizeof(FollowRecord)) == 0;
                               });
  if (!same) {
    glBindVertexArray(0);
    if (!g.follow) g.follow = Buffer::create();
    glBindBuffer(GL_ARRAY_BUFFER, g.follow.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(std::max<std::size_t>(records.size(), 1) * sizeof(FollowRecord)),
                 records.empty() ? nullptr : records.data(), GL_DYNAMIC_DRAW);
    for (const LayerGl::TileGl& t : g.tiles) {
      if (!t.vao) continue;
      glBindVertexArray(t.vao.id());
      glBindBuffer(GL_ARRAY_BUFFER, g.follow.id());
      for (GLuint a = 0; a < 6; ++a) {
        glEnableVertexAttribArray(7 + a);
        glVertexAttribPointer(7 + a, 3, GL_FLOAT, GL_FALSE, sizeof(FollowRecord),
                              reinterpret_cast<const void*>(a * 3 * sizeof(float)));
        glVertexAttribDivisor(7 + a, 1);
      }
      glBindVertexArray(0);
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    g.follow_uploaded = std::move(records);
  }
  if (d.lattice()) {
    if (!follow.lattice) throw std::invalid_argument("DdmGl: a following layer with a lattice needs its buffers");
    const core::Embedding& e = d.embedding();
    glUniformMatrix3fv(p.uniform("u_embed_linear"), 1, GL_FALSE, glm::value_ptr(glm::mat3(e.linear)));
    p.set("u_embed_shift", glm::vec3(e.offset));
    glUniformMatrix3fv(p.uniform("u_embed_inverse"), 1, GL_FALSE, glm::value_ptr(glm::mat3(glm::inverse(e.linear))));
    p.set("u_param_offset", glm::vec3(d.offset()));
    glUniform1i(p.uniform("u_identity_outside"), d.identity_outside() ? 1 : 0);
    follow.lattice->bind();
  }
}

void DdmGl::ensure_levels(LayerGl& g) {
  if (g.levels_made) return;
  g.levels_made = true;
  if (g.materials) return;  // texture-mapped tiles draw their material runs at level 0
  glBindVertexArray(0);
  const core::DdmLayer& l = *g.layer;
  for (std::size_t t = 0; t < l.tiles.size(); ++t) {
    LayerGl::TileGl& tile = g.tiles[t];
    if (tile.instance_count == 0 || tile.index_count == 0) continue;
    const core::TriMesh& mesh = l.tiles[t].mesh;
    // Untextured: the full list is the tile's triangles in order (one material run). A morph partner takes the
    // same triangles.
    std::vector<std::uint32_t> idx;
    idx.reserve(std::size_t(tile.index_count) * 3 / 2);
    for (const glm::uvec3& f : mesh.triangles) idx.insert(idx.end(), {f.x, f.y, f.z});
    for (int k = 1; k < kDdmLodLevels; ++k) {
      const std::size_t target = std::max(kDdmLodMinVertices, mesh.vertex_count() >> (2 * k));
      if (target >= tile.level_vertices[tile.levels - 1]) break;
      const std::vector<glm::uvec3> coarse = core::decimated_triangles(mesh, target);
      const std::size_t used = core::used_vertex_count(coarse, mesh.vertex_count());
      if (used >= tile.level_vertices[tile.levels - 1]) break;
      tile.level_first[k] = GLsizei(idx.size());
      tile.level_count[k] = GLsizei(3 * coarse.size());
      tile.level_vertices[k] = used;
      for (const glm::uvec3& f : coarse) idx.insert(idx.end(), {f.x, f.y, f.z});
      tile.levels = k + 1;
    }
    if (tile.levels == 1) continue;
    // The same buffer (the tile's vertex arrays keep it as their element buffer), through GL_ARRAY_BUFFER.
    glBindBuffer(GL_ARRAY_BUFFER, tile.indices.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(idx.size() * sizeof(std::uint32_t)), idx.data(), GL_STATIC_DRAW);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  g.selected_version = 0;  // the runs per level are made again
  check_gl_error("DdmGl: tile levels upload");
}

void DdmGl::select(LayerGl& g, const DdmSelection& selection) {
  ensure_levels(g);
  if (selection.version == g.selected_version && g.selected) return;
  const core::DdmLayer& l = *g.layer;
  if (selection.drawn.size() != l.instances.size())
    throw layer_error(l, "a selection of " + std::to_string(selection.drawn.size()) + " flags for " +
                             std::to_string(l.instances.size()) + " instances");
  std::vector<InstanceRecord> kept;
  kept.reserve(g.records.size());
  g.selected_vertices = 0;
  for (LayerGl::TileGl& t : g.tiles)
    for (int k = 0; k < kDdmLodLevels; ++k) {
      // Level k's run: the instances flagged 1 + k (or finer than the tile has, at its coarsest level).
      t.selected_first[k] = GLuint(kept.size());
      if (k < t.levels)
        for (GLuint pos = t.first_instance; pos < t.first_instance + GLuint(t.instance_count); ++pos) {
          const int flag = selection.drawn[g.grouped[pos]];
          if (flag > 0 && std::min(flag - 1, t.levels - 1) == k) kept.push_back(g.records[pos]);
        }
      t.selected_count[k] = GLsizei(kept.size() - t.selected_first[k]);
      g.selected_vertices += std::size_t(t.selected_count[k]) * t.level_vertices[k];
    }
  glBindVertexArray(0);
  if (!g.selected) g.selected = Buffer::create();
  glBindBuffer(GL_ARRAY_BUFFER, g.selected.id());
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(std::max<std::size_t>(kept.size(), 1) * sizeof(InstanceRecord)),
               kept.empty() ? nullptr : kept.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  for (LayerGl::TileGl& t : g.tiles)
    if (t.instance_count > 0 && !t.selected_vao) {
      t.selected_vao = VertexArray::create();
      record_tile_vao(LayerGl::buffers(t), t.selected_vao.id(), g.selected.id());
    }
  g.selected_version = selection.version;
  check_gl_error("DdmGl: selection upload");
}

std::shared_ptr<const core::MaterialSet> DdmGl::materials(const std::shared_ptr<const core::DdmLayer>& layer,
                                                          const glm::dvec3& untextured_color) {
  if (!layer) return nullptr;
  LayerGl& g = layer_for(layer);
  if (g.materials && g.materials_color != untextured_color)  // the same slots; images shared, not re-read
    g.materials = core::ddm_tile_materials(layer->tiles, untextured_color).set, g.materials_color = untextured_color;
  return g.materials;
}

std::size_t DdmGl::draw(const std::shared_ptr<const core::DdmLayer>& layer, const DdmPose& pose,
                        const glm::dmat4& model, const ShaderProgram& program, const DdmFollow* follow,
                        const DdmSelection* selection, const DdmMaterialBinder* bind_material) {
  if (follow) selection = nullptr;  // follow records are per instance of the whole layer
  constexpr const char* where = "DdmGl::draw";
  if (!layer) throw std::invalid_argument(std::string(where) + ": no layer");
  LayerGl& g = layer_for(layer);
  if (g.vertices == 0) return 0;
  if (selection) select(g, *selection);
  pose_tiles(g, *layer, pose.time_s);
  const MapsGl& maps = maps_for(layer->maps);
  set_uniforms(program, *layer, pose, follow ? follow->deformation->model() : model);
  if (follow) bind_follow(g, program, *follow);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMapsBinding, maps.samples.id());
  for (const LayerGl::TileGl& t : g.tiles) {
    if (t.index_count == 0 || t.instance_count == 0) continue;
    glBindVertexArray(selection ? t.selected_vao.id() : t.vao.id());
    if (!bind_material || !g.materials) {
      for (int k = 0; k < (selection ? t.levels : 1); ++k) {
        const GLsizei count = selection ? t.selected_count[k] : t.instance_count;
        if (count == 0) continue;
        glDrawElementsInstancedBaseInstance(
            GL_TRIANGLES, t.level_count[k], GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(std::size_t(t.level_first[k]) * sizeof(std::uint32_t)), count,
            selection ? t.selected_first[k] : t.first_instance);
      }
      continue;
    }
    // Texture-mapped tiles have level 0 only.
    const GLsizei count = selection ? t.selected_count[0] : t.instance_count;
    const GLuint first = selection ? t.selected_first[0] : t.first_instance;
    if (count == 0) continue;
    for (const LayerGl::TileGl::SlotRange& r : t.ranges) {
      (*bind_material)(r.slot);
      glDrawElementsInstancedBaseInstance(GL_TRIANGLES, r.count, GL_UNSIGNED_INT,
                                          reinterpret_cast<const void*>(std::size_t(r.first) * sizeof(std::uint32_t)),
                                          count, first);
    }
  }
  glBindVertexArray(0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMapsBinding, 0);
  check_gl_error(where);
  return selection ? g.selected_vertices : g.vertices;
}

DdmCapture DdmGl::capture(const std::shared_ptr<const core::DdmLayer>& layer, const DdmPose& pose,
                          const DdmFollow* follow) {
  constexpr const char* where = "DdmGl::capture";
  if (!layer) throw std::invalid_argument(std::string(where) + ": no layer");
  LayerGl& g = layer_for(layer);
  DdmCapture out;
  if (g.vertices == 0) return out;
  pose_tiles(g, *layer, pose.time_s);
  const MapsGl& maps = maps_for(layer->maps);
  ShaderDefines defines;
  if (follow) defines.push_back({"FOLLOW", ""});
  if (follow && follow->deformation->lattice()) defines.push_back({"FFD", ""});
  const ShaderProgram& prog = programs_->get({"ddm.vert.glsl"}, defines, {"v_world", "v_normal"});
  if (g.vertices > capture_capacity_) {
    const auto bytes = GLsizeiptr(g.vertices * 3 * sizeof(float));
    capture_positions_ = upload_array(GL_TRANSFORM_FEEDBACK_BUFFER, nullptr, std::size_t(bytes));
    capture_normals_ = upload_array(GL_TRANSFORM_FEEDBACK_BUFFER, nullptr, std::size_t(bytes));
    capture_capacity_ = g.vertices;
  }
  const GLint previous_fbo = bind_complete_draw_framebuffer(fallback_fbo_, fallback_rb_);  // surfaceless EGL
  prog.use();
  prog.set("u_view_proj", glm::mat4(1.0f));
  set_uniforms(prog, *layer, pose, follow ? follow->deformation->model() : glm::dmat4(1.0));
  if (follow) bind_follow(g, prog, *follow);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMapsBinding, maps.samples.id());
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, capture_positions_.id());
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 1, capture_normals_.id());
  const bool discard_was_on = glIsEnabled(GL_RASTERIZER_DISCARD);
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  for (const LayerGl::TileGl& t : g.tiles)  // successive draws append: tile groups one after another, instance-major
    if (t.instance_count > 0 && t.vertex_count > 0) {
      glBindVertexArray(t.vao.id());
      glDrawArraysInstancedBaseInstance(GL_POINTS, 0, t.vertex_count, t.instance_count, t.first_instance);
    }
  glEndTransformFeedback();
  if (!discard_was_on) glDisable(GL_RASTERIZER_DISCARD);
  glBindVertexArray(0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMapsBinding, 0);
  std::vector<glm::vec3> pos(g.vertices), nrm(g.vertices);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, capture_positions_.id());
  glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, GLsizeiptr(pos.size() * sizeof(glm::vec3)), pos.data());
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, capture_normals_.id());
  glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, GLsizeiptr(nrm.size() * sizeof(glm::vec3)), nrm.data());
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, 0);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 1, 0);
  glUseProgram(0);
  restore_draw_framebuffer(previous_fbo);
  check_gl_error(where);
  // Grouped (by tile) order → the layer's instance order.
  const core::DdmLayer& l = *layer;
  std::vector<std::size_t> first(l.instances.size() + 1, 0);
  for (std::size_t k = 0; k < l.instances.size(); ++k)
    first[k + 1] = first[k] + l.tiles[std::size_t(l.instances[k].tile)].mesh.vertex_count();
  out.positions.resize(g.vertices);
  out.normals.resize(g.vertices);
  std::size_t src = 0;
  for (std::size_t k : g.grouped) {
    const std::size_t nv = first[k + 1] - first[k];
    std::copy_n(pos.begin() + std::ptrdiff_t(src), nv, out.positions.begin() + std::ptrdiff_t(first[k]));
    std::copy_n(nrm.begin() + std::ptrdiff_t(src), nv, out.normals.begin() + std::ptrdiff_t(first[k]));
    src += nv;
  }
  return out;
}

void DdmGl::release_unused(const std::unordered_set<const core::DdmLayer*>& live) {
  std::erase_if(layers_, [&](const auto& kv) { return !live.count(kv.first); });
  std::unordered_set<const core::DdmMaps*> live_maps;
  for (const auto& [ptr, g] : layers_)
    if (g->layer->maps) live_maps.insert(g->layer->maps.get());
  for (const core::DdmLayer* l : live)
    if (l && l->maps) live_maps.insert(l->maps.get());
  std::erase_if(maps_, [&](const auto& kv) { return !live_maps.count(kv.first); });
}

}  // namespace trispline::gpu
