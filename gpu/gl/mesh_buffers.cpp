#include "gpu/gl/mesh_buffers.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace trispline::gpu {
namespace {

std::vector<float> to_float3(const std::vector<glm::dvec3>& v) {
  std::vector<float> out(v.size() * 3);
  for (std::size_t i = 0; i < v.size(); ++i) {
    out[3 * i + 0] = float(v[i].x);
    out[3 * i + 1] = float(v[i].y);
    out[3 * i + 2] = float(v[i].z);
  }
  return out;
}

}  // namespace

std::vector<glm::vec3> vertex_normals(const core::TriMesh& mesh) {
  std::vector<glm::dvec3> acc(mesh.positions.size(), glm::dvec3(0.0));
  for (const glm::uvec3& f : mesh.triangles) {
    const glm::dvec3 n =
        glm::cross(mesh.positions[f.y] - mesh.positions[f.x], mesh.positions[f.z] - mesh.positions[f.x]);
    acc[f.x] += n;
    acc[f.y] += n;
    acc[f.z] += n;
  }
  std::vector<glm::vec3> out(acc.size());
  for (std::size_t i = 0; i < acc.size(); ++i) {
    const double len = glm::length(acc[i]);
    out[i] = len > 0.0 ? glm::vec3(acc[i] / len) : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return out;
}

void MeshBuffers::upload(const core::TriMesh& mesh) {
  const std::size_t nv = mesh.positions.size();
  for (const glm::uvec3& f : mesh.triangles)
    if (f.x >= nv || f.y >= nv || f.z >= nv)
      throw std::invalid_argument("MeshBuffers::upload: triangle index out of range (" + std::to_string(nv) +
                                  " vertices)");
  if (!mesh.face_material.empty() && mesh.face_material.size() != mesh.triangles.size())
    throw std::invalid_argument("MeshBuffers::upload: face_material has " + std::to_string(mesh.face_material.size()) +
                                " entries for " + std::to_string(mesh.triangles.size()) + " triangles");
  // Stable order by material slot (kMaterialInside, the largest, last): a counting sort over the slots present.
  std::size_t inside = 0;
  std::vector<MaterialRange> ranges;
  std::vector<glm::uvec3> ordered;
  if (!mesh.face_material.empty()) {
    std::vector<std::size_t> count(std::size_t(core::kMaterialInside) + 1, 0);
    for (core::MaterialSlot m : mesh.face_material) ++count[m];
    std::vector<std::size_t> start(count.size(), 0);
    std::size_t at = 0;
    for (std::size_t m = 0; m < count.size(); ++m) {
      start[m] = at;
      if (count[m] > 0) ranges.push_back({core::MaterialSlot(m), {at, count[m]}});
      at += count[m];
    }
    inside = count[core::kMaterialInside];
    if (ranges.size() > 1) {
      ordered.resize(mesh.triangles.size());
      for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
        ordered[start[mesh.face_material[f]]++] = mesh.triangles[f];
    }
  } else if (!mesh.triangles.empty()) {
    ranges.push_back({core::MaterialSlot(0), {0, mesh.triangles.size()}});
  }
  const std::vector<glm::uvec3>& tris = ordered.empty() ? mesh.triangles : ordered;
  if (!vao_) {
    vao_ = VertexArray::create();
    positions_ = Buffer::create();
    normals_ = Buffer::create();
    uvs_ = Buffer::create();
    indices_ = Buffer::create();
  }
  std::vector<float> pos = to_float3(mesh.positions);
  std::vector<float> nrm;
  if (mesh.normals.size() == nv) {
    nrm = to_float3(mesh.normals);
  } else {
    const std::vector<glm::vec3> n = vertex_normals(mesh);
    nrm.resize(nv * 3);
    for (std::size_t i = 0; i < nv; ++i) {
      nrm[3 * i + 0] = n[i].x;
      nrm[3 * i + 1] = n[i].y;
      nrm[3 * i + 2] = n[i].z;
    }
  }
  glBindVertexArray(vao_.id());
  float_attribute(0, positions_.id(), 3);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(pos.size() * sizeof(float)), pos.data(), GL_DYNAMIC_DRAW);
  float_attribute(1, normals_.id(), 3);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(nrm.size() * sizeof(float)), nrm.data(), GL_DYNAMIC_DRAW);
  has_uvs_ = nv > 0 && mesh.uvs.size() == nv;
  if (has_uvs_) {
    std::vector<float> uv(nv * 2);
    for (std::size_t i = 0; i < nv; ++i) {
      uv[2 * i + 0] = float(mesh.uvs[i].x);
      uv[2 * i + 1] = float(mesh.uvs[i].y);
    }
    glBindBuffer(GL_ARRAY_BUFFER, uvs_.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(uv.size() * sizeof(float)), uv.data(), GL_STATIC_DRAW);
  }
  bind_uvs_to_bound_vao();
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.id());  // recorded in the VAO
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(tris.size() * sizeof(glm::uvec3)), tris.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  vertex_count_ = nv;
  triangle_count_ = mesh.triangles.size();
  inside_count_ = inside;
  material_ranges_ = std::move(ranges);
}

void MeshBuffers::bind_uvs_to_bound_vao() const {
  if (has_uvs_) {
    float_attribute(3, uvs_.id(), 2);
  } else {
    glDisableVertexAttribArray(3);
    glVertexAttrib2f(3, 0.0f, 0.0f);
  }
}

void MeshBuffers::update_vertices(const std::vector<glm::dvec3>& positions, const std::vector<glm::dvec3>& normals) {
  if (positions.size() != vertex_count_ || (!normals.empty() && normals.size() != vertex_count_))
    throw std::invalid_argument("MeshBuffers::update_vertices: expected " + std::to_string(vertex_count_) +
                                " vertices, got " + std::to_string(positions.size()));
  const std::vector<float> pos = to_float3(positions);
  glBindBuffer(GL_ARRAY_BUFFER, positions_.id());
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(pos.size() * sizeof(float)), pos.data());
  if (!normals.empty()) {
    const std::vector<float> nrm = to_float3(normals);
    glBindBuffer(GL_ARRAY_BUFFER, normals_.id());
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(nrm.size() * sizeof(float)), nrm.data());
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void MeshBuffers::update_vertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals) {
  if (positions.size() != vertex_count_ || (!normals.empty() && normals.size() != vertex_count_))
    throw std::invalid_argument("MeshBuffers::update_vertices: expected " + std::to_string(vertex_count_) +
                                " vertices, got " + std::to_string(positions.size()));
  glBindBuffer(GL_ARRAY_BUFFER, positions_.id());
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(positions.size() * sizeof(glm::vec3)), positions.data());
  if (!normals.empty()) {
    glBindBuffer(GL_ARRAY_BUFFER, normals_.id());
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(normals.size() * sizeof(glm::vec3)), normals.data());
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void MeshBuffers::draw_triangles() const {
  if (triangle_count_ == 0) return;
  glBindVertexArray(vao_.id());
  glDrawElements(GL_TRIANGLES, GLsizei(triangle_count_ * 3), GL_UNSIGNED_INT, nullptr);
}

void MeshBuffers::draw_range(TriangleRange range) const {
  if (range.count == 0) return;
  glBindVertexArray(vao_.id());
  glDrawElements(GL_TRIANGLES, GLsizei(range.count * 3), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(range.first * sizeof(glm::uvec3)));
}

}  // namespace trispline::gpu
