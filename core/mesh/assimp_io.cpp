#include "core/mesh/assimp_io.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/MemoryIOWrapper.h>

#include <assimp/DefaultLogger.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <cstring>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace trispline::core {
namespace {

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

// assimp reports what it repaired only in its log: an OFF face index out of range is clamped to the last vertex with
// a warning, for instance. Warnings and errors of the import running on this thread are collected here (assimp's
// logger is one per process; the buffer is per thread, so loads on several threads keep theirs apart).
thread_local std::vector<std::string>* t_warnings = nullptr;

struct WarningSink : Assimp::LogStream {
  void write(const char* message) override {
    if (!t_warnings) return;
    std::string m = message;
    while (!m.empty() && (m.back() == '\n' || m.back() == '\r')) m.pop_back();
    t_warnings->push_back(std::move(m));
  }
};

void install_warning_sink() {
  static std::once_flag once;
  std::call_once(once, [] {
    Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);  // no default streams (no file, no console)
    Assimp::DefaultLogger::get()->attachStream(new WarningSink, Assimp::Logger::Warn | Assimp::Logger::Err);
  });
}

// A warning that means assimp changed or dropped data of the file (rather than noting a harmless oddity).
bool is_repair(const std::string& w) {
  for (const char* word :
       {"out of range", "Out of range", "clamp", "skipping", "Skipping", "ignoring", "Ignoring", "invalid", "Invalid",
        "truncat", "Truncat", "unexpected end", "Unexpected end", "incorrect", "not allowed", "n't allowed"})
    if (w.find(word) != std::string::npos) return true;
  return false;
}

// The only file an import may open: the bytes already read (and checked), under one name. Every other name does not
// exist, so an OBJ's `mtllib` and the material file assimp falls back to are never opened. (assimp's own
// ReadFileFromMemory serves its buffer for every name that starts with its magic name, so the OBJ importer's
// fallback "<name>.mtl" read the OBJ itself as a material library, whose parser then wrote through a null material:
// a crash found by fuzz_mesh_obj.)
class OneFileIOSystem : public Assimp::IOSystem {
 public:
  OneFileIOSystem(std::string name, const std::vector<unsigned char>& bytes) : name_(std::move(name)), bytes_(bytes) {}
  bool Exists(const char* file) const override { return file && name_ == file; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!Exists(file) || !mode || std::strchr(mode, 'w') || std::strchr(mode, 'a')) return nullptr;
    return new Assimp::MemoryIOStream(bytes_.data(), bytes_.size(), false);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  std::string name_;
  const std::vector<unsigned char>& bytes_;
};

// One vertex of the joined mesh as the file gave it: position, normal, uv (unused parts zero). Welding compares the
// bits, so -0.0 and 0.0 stay apart and NaNs never merge (both are refused later anyway).
struct VertexKey {
  double v[8] = {};
  bool operator==(const VertexKey& o) const { return std::memcmp(v, o.v, sizeof v) == 0; }
};
struct VertexKeyHash {
  std::size_t operator()(const VertexKey& k) const {
    std::size_t h = 1469598103934665603ull;
    const auto* b = reinterpret_cast<const unsigned char*>(k.v);
    for (std::size_t i = 0; i < sizeof k.v; ++i) h = (h ^ b[i]) * 1099511628211ull;
    return h;
  }
};

struct Joiner {
  bool normals = false, uvs = false;
  TriMesh out;
  std::unordered_map<VertexKey, unsigned, VertexKeyHash> index;

  unsigned add(const glm::dvec3& p, const glm::dvec3& n, const glm::dvec2& uv) {
    VertexKey k;
    k.v[0] = p.x, k.v[1] = p.y, k.v[2] = p.z;
    if (normals) k.v[3] = n.x, k.v[4] = n.y, k.v[5] = n.z;
    if (uvs) k.v[6] = uv.x, k.v[7] = uv.y;
    const auto [it, fresh] = index.try_emplace(k, static_cast<unsigned>(out.positions.size()));
    if (fresh) {
      out.positions.push_back(p);
      if (normals) out.normals.push_back(n);
      if (uvs) out.uvs.push_back(uv);
    }
    return it->second;
  }
};

glm::dmat4 to_glm(const aiMatrix4x4& m) {  // assimp is row-major (a1..a4 the first row), glm column-major
  glm::dmat4 g(1.0);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) g[c][r] = m[r][c];
  return g;
}

// Meshes in node order, each with the world transform of the node that holds it (a mesh held by no node once,
// untransformed, so no face of the file is left out).
struct Placed {
  const aiMesh* mesh;
  glm::dmat4 world;
};
void collect(const aiScene& scene, const aiNode* node, const glm::dmat4& parent, int depth, std::vector<Placed>& out,
             std::vector<bool>& used, const std::filesystem::path& path) {
  if (depth > 256) throw MeshIoError(quoted(path) + ": node hierarchy deeper than 256 levels");
  const glm::dmat4 world = parent * to_glm(node->mTransformation);
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const unsigned m = node->mMeshes[i];
    if (m >= scene.mNumMeshes) throw MeshIoError(quoted(path) + ": node refers to a missing mesh");
    out.push_back({scene.mMeshes[m], world});
    used[m] = true;
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    collect(scene, node->mChildren[c], world, depth + 1, out, used, path);
}

}  // namespace

TriMesh read_assimp_mesh(const std::filesystem::path& path, const std::string& ext,
                         const std::vector<unsigned char>& bytes, MeshLoadReport& report) {
  Assimp::Importer importer;
  install_warning_sink();
  std::vector<std::string> warnings;
  t_warnings = &warnings;
  struct StopCollecting {
    ~StopCollecting() { t_warnings = nullptr; }
  } stop_collecting;
  // Two steps: read and validate, then triangulate. assimp's importers can leave a mesh whose primitive-type flags
  // disagree with its faces (a PLY face list of 0, 1 or 2 corners), and aiProcess_Triangulate then fails an
  // ai_assert, which aborts the process. Between the steps the flags are set from the faces themselves.
  const std::string name = "mesh" + ext;
  importer.SetIOHandler(new OneFileIOSystem(name, bytes));  // the importer owns it
  const aiScene* scene = importer.ReadFile(name, aiProcess_ValidateDataStructure);
  auto refuse_if_repaired = [&] {
    for (const std::string& w : warnings)
      if (is_repair(w)) throw MeshIoError(quoted(path) + ": cannot parse " + ext.substr(1) + " file: " + w);
  };
  if (scene) refuse_if_repaired();
  if (!scene) {
    std::string why = importer.GetErrorString();
    if (why.empty()) why = "unknown reason";
    for (const char* empty : {"contains no faces", "contains no vertices", "too small", "no valid vertices"})
      if (why.find(empty) != std::string::npos)
        throw MeshIoError(quoted(path) + ": empty mesh (no triangles): a point cloud or no geometry (assimp: " + why +
                          ")");
    throw MeshIoError(quoted(path) + ": cannot parse " + ext.substr(1) + " file: " + why);
  }
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode)
    throw MeshIoError(quoted(path) + ": cannot parse " + ext.substr(1) + " file: the file holds no complete mesh");
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    aiMesh& mesh = *scene->mMeshes[m];  // owned by `importer`; only its flags are corrected
    unsigned types = 0;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const unsigned n = mesh.mFaces[f].mNumIndices;
      if (n == 0) throw MeshIoError(quoted(path) + ": cannot parse " + ext.substr(1) + " file: a face with no corners");
      types |= n == 1 ? aiPrimitiveType_POINT : n == 2 ? aiPrimitiveType_LINE
                                              : n == 3 ? aiPrimitiveType_TRIANGLE : aiPrimitiveType_POLYGON;
    }
    mesh.mPrimitiveTypes = types;
  }
  unsigned flags = aiProcess_Triangulate;
  if (ext == ".stl") {  // per-face normals: dropped, so the corners weld into a connected mesh
    importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS);
    flags |= aiProcess_RemoveComponent;
  }
  scene = importer.ApplyPostProcessing(flags);
  if (!scene) throw MeshIoError(quoted(path) + ": cannot parse " + ext.substr(1) + " file: " + importer.GetErrorString());
  refuse_if_repaired();

  std::vector<Placed> placed;
  std::vector<bool> used(scene->mNumMeshes, false);
  collect(*scene, scene->mRootNode, glm::dmat4(1.0), 0, placed, used, path);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    if (!used[m]) placed.push_back({scene->mMeshes[m], glm::dmat4(1.0)});

  Joiner join;
  join.normals = !placed.empty();
  join.uvs = false;
  for (const Placed& pm : placed) {
    join.normals = join.normals && pm.mesh->HasNormals();
    join.uvs = join.uvs || pm.mesh->HasTextureCoords(0);
  }
  std::size_t triangles = 0;
  for (const Placed& pm : placed)
    for (unsigned f = 0; f < pm.mesh->mNumFaces; ++f) triangles += pm.mesh->mFaces[f].mNumIndices == 3;
  join.out.triangles.reserve(triangles);

  for (const Placed& pm : placed) {
    const aiMesh& m = *pm.mesh;
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(pm.world)));
    std::vector<unsigned> ids(m.mNumVertices, ~0u);  // file corner → joined vertex, made on first use
    auto vertex = [&](unsigned i) {
      if (ids[i] != ~0u) return ids[i];
      const aiVector3D& p = m.mVertices[i];
      const glm::dvec3 pos = glm::dvec3(pm.world * glm::dvec4(p.x, p.y, p.z, 1.0));
      glm::dvec3 n(0.0);
      if (join.normals) {
        const aiVector3D& fn = m.mNormals[i];
        n = normal_matrix * glm::dvec3(fn.x, fn.y, fn.z);
        const double len = glm::length(n);
        if (len > 0) n /= len;
      }
      glm::dvec2 uv(0.0);
      if (join.uvs && m.HasTextureCoords(0)) uv = {m.mTextureCoords[0][i].x, m.mTextureCoords[0][i].y};
      return ids[i] = join.add(pos, n, uv);
    };
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices == 1) {
        ++report.ignored_points;
      } else if (face.mNumIndices == 2) {
        ++report.ignored_lines;
      } else if (face.mNumIndices == 3) {
        for (unsigned k = 0; k < 3; ++k)
          if (face.mIndices[k] >= m.mNumVertices)
            throw MeshIoError(quoted(path) + ": vertex index out of range in face " + std::to_string(f));
        join.out.triangles.push_back({vertex(face.mIndices[0]), vertex(face.mIndices[1]), vertex(face.mIndices[2])});
      } else {  // aiProcess_Triangulate leaves nothing larger; refuse rather than drop if it ever does
        throw MeshIoError(quoted(path) + ": a face of " + std::to_string(face.mNumIndices) +
                          " corners was not triangulated");
      }
    }
  }
  report.faces = join.out.triangles.size();
  if (join.out.triangles.empty()) {
    throw MeshIoError(quoted(path) + ": empty mesh (no triangles): only " + std::to_string(report.ignored_points) +
                      " points and " + std::to_string(report.ignored_lines) + " lines (trispline loads surfaces)");
  }
  return std::move(join.out);
}

}  // namespace trispline::core
