#include "core/mesh/assimp_io.h"

#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/DefaultLogger.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "core/mesh/assimp_material.h"
#include "core/mesh/file_check.h"
#include "core/mesh/mesh_precheck.h"
#include "core/mesh/model_load.h"
#include "core/mesh/path_quote.h"

namespace trispline::core {
namespace {

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

// The only files an import may open: the bytes already read (and checked), under one name, and for an OBJ read with
// materials its checked material libraries under kServedMtlName. Every other name does not exist, so the material
// file assimp falls back to is never opened, and the model is never read as its own material library. (assimp's own
// ReadFileFromMemory serves its buffer for every name that starts with its magic name, so the OBJ importer's
// fallback "<name>.mtl" read the OBJ itself as a material library, whose parser then wrote through a null material:
// a crash found by fuzz_mesh_obj.)
class ServedFilesIOSystem : public Assimp::IOSystem {
 public:
  ServedFilesIOSystem(std::string name, const std::vector<unsigned char>& bytes, const std::string* mtl)
      : name_(std::move(name)), bytes_(bytes), mtl_(mtl) {}
  bool Exists(const char* file) const override {
    return file && (name_ == file || (mtl_ && std::strcmp(file, kServedMtlName) == 0));
  }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!Exists(file) || !mode || std::strchr(mode, 'w') || std::strchr(mode, 'a')) return nullptr;
    if (name_ == file) return new Assimp::MemoryIOStream(bytes_.data(), bytes_.size(), false);
    return new Assimp::MemoryIOStream(reinterpret_cast<const std::uint8_t*>(mtl_->data()), mtl_->size(), false);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  std::string name_;
  const std::vector<unsigned char>& bytes_;
  const std::string* mtl_;  // null: no material library is served
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
  const aiNode* node;  // null for a mesh held by no node
};
void collect(const aiScene& scene, const aiNode* node, const glm::dmat4& parent, int depth, std::vector<Placed>& out,
             std::vector<bool>& used, const std::filesystem::path& path) {
  if (depth > 256) throw MeshIoError(quoted(path) + ": node hierarchy deeper than 256 levels");
  const glm::dmat4 world = parent * to_glm(node->mTransformation);
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const unsigned m = node->mMeshes[i];
    if (m >= scene.mNumMeshes) throw MeshIoError(quoted(path) + ": node refers to a missing mesh");
    out.push_back({scene.mMeshes[m], world, node});
    used[m] = true;
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    collect(scene, node->mChildren[c], world, depth + 1, out, used, path);
}

// The OBJ's material libraries (names as written after `mtllib`) read from its folder, each checked and rewritten
// (check_mtl_text), joined; a library that cannot be read is left out and named in `warnings`.
std::string served_mtl(const std::filesystem::path& path, const std::vector<std::string>& names,
                       std::vector<std::string>& warnings) {
  std::string joined;
  for (const std::string& name : names) {
    std::vector<unsigned char> bytes;
    try {
      bytes = read_model_side_file(path, name, kMaxMtlFileBytes);
    } catch (const MeshIoError& e) {
      warnings.push_back(std::string("material library ") + e.what() + " (its materials are left at their defaults)");
      continue;
    }
    joined += check_mtl_text(path.parent_path() / name, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
  }
  return joined;
}

}  // namespace

bool is_assimp_extension(const std::string& e) {
  return e == ".obj" || e == ".ply" || e == ".off" || e == ".stl" || e == ".dae" || e == ".fbx";
}

AssimpModel read_assimp_file(const std::filesystem::path& path, const std::string& ext, const MeshLoadOptions& options,
                             MeshLoadReport& report, bool materials) {
  report.loader = "assimp";
  check_input_file(path, kMaxMeshFileBytes, "mesh files");
  {  // what the size and the head tell, before the whole file is read
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> head(kMeshHeadBytes);
    in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw MeshIoError(quoted(path) + ": cannot access: " + ec.message());
    precheck_mesh_head(path, ext, head, size);
  }
  std::vector<unsigned char> bytes = read_input_file(path, kMaxMeshFileBytes, "mesh files");
  std::vector<std::string> mtllibs;
  prepare_mesh_bytes(path, ext, bytes, materials && ext == ".obj" ? &mtllibs : nullptr);
  precheck_mesh_file(path, ext, bytes);
  AssimpModel m = read_assimp_mesh(path, ext, bytes, report, materials, &mtllibs);
  if ((report.ignored_points || report.ignored_lines) && !options.ignore_loose)
    throw MeshIoError(quoted(path) + ": holds " + std::to_string(report.ignored_points) + " point and " +
                      std::to_string(report.ignored_lines) + " line elements besides its " +
                      std::to_string(report.faces) +
                      " faces; trispline loads surfaces only (delete the loose geometry, or load with "
                      "\"loose\":\"ignore\" to leave it out)");
  return m;
}
AssimpModel read_assimp_mesh(const std::filesystem::path& path, const std::string& ext,
                             const std::vector<unsigned char>& bytes, MeshLoadReport& report, bool materials,
                             const std::vector<std::string>* mtllibs) {
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
  AssimpModel result;
  std::string mtl;
  const bool serve_mtl = materials && ext == ".obj" && mtllibs && !mtllibs->empty();
  if (serve_mtl) mtl = served_mtl(path, *mtllibs, result.warnings);
  importer.SetIOHandler(new ServedFilesIOSystem(name, bytes, serve_mtl ? &mtl : nullptr));  // the importer owns it
  // Collada nodes keep their `name` attribute (as Blender's importer does), not their `id`.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_USE_COLLADA_NAMES, true);
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
      types |= n == 1   ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    mesh.mPrimitiveTypes = types;
  }
  unsigned flags = aiProcess_Triangulate | aiProcess_FlipUVs;  // uvs: glTF's convention (model_load.h)
  if (ext == ".stl") {  // per-face normals: dropped, so the corners weld into a connected mesh
    importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS);
    flags |= aiProcess_RemoveComponent;
  }
  scene = importer.ApplyPostProcessing(flags);
  if (!scene)
    throw MeshIoError(quoted(path) + ": cannot parse " + ext.substr(1) + " file: " + importer.GetErrorString());
  refuse_if_repaired();

  std::vector<Placed> placed;
  std::vector<bool> used(scene->mNumMeshes, false);
  collect(*scene, scene->mRootNode, glm::dmat4(1.0), 0, placed, used, path);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    if (!used[m]) placed.push_back({scene->mMeshes[m], glm::dmat4(1.0), nullptr});

  // Parts: one per mesh node (consecutive entries of `placed` share their node), for scene formats only.
  const bool scene_format = ext == ".dae" || ext == ".fbx";
  std::size_t mesh_nodes = 0;
  for (std::size_t i = 0; i < placed.size(); ++i)
    mesh_nodes += i == 0 || placed[i].node != placed[i - 1].node || !placed[i].node;
  const bool with_parts = scene_format && mesh_nodes > 1;

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
  if (materials) join.out.face_material.reserve(triangles);

  std::vector<unsigned> slots_used;             // scene material index of slot k
  std::map<unsigned, MaterialSlot> slot_of;     // scene material index → slot
  std::map<std::vector<unsigned>, int> shapes;  // a node's mesh list → MeshPart::mesh_index (instances share it)
  for (std::size_t i = 0; i < placed.size(); ++i) {
    const Placed& pm = placed[i];
    const bool new_part = i == 0 || pm.node != placed[i - 1].node || !pm.node;
    if (with_parts && new_part) {
      if (!result.parts.empty()) {
        MeshPart& last = result.parts.back();
        last.vertex_count = static_cast<std::uint32_t>(join.out.positions.size()) - last.first_vertex;
        last.triangle_count = static_cast<std::uint32_t>(join.out.triangles.size()) - last.first_triangle;
      }
      join.index.clear();  // welded within a part only
      MeshPart part;
      std::vector<unsigned> shape;
      if (pm.node) {
        part.name = pm.node->mName.C_Str();
        shape.assign(pm.node->mMeshes, pm.node->mMeshes + pm.node->mNumMeshes);
      } else {
        shape.push_back(static_cast<unsigned>(std::find(scene->mMeshes, scene->mMeshes + scene->mNumMeshes, pm.mesh) -
                                              scene->mMeshes) |
                        0x80000000u);
      }
      part.mesh_index = shapes.try_emplace(shape, static_cast<int>(shapes.size())).first->second;
      part.world = pm.world;
      part.first_vertex = static_cast<std::uint32_t>(join.out.positions.size());
      part.first_triangle = static_cast<std::uint32_t>(join.out.triangles.size());
      result.parts.push_back(std::move(part));
    }
    const aiMesh& m = *pm.mesh;
    MaterialSlot slot = 0;
    bool has_triangles = false;
    for (unsigned f = 0; f < m.mNumFaces && !has_triangles; ++f) has_triangles = m.mFaces[f].mNumIndices == 3;
    if (materials && has_triangles) {
      const auto [it, fresh] = slot_of.try_emplace(m.mMaterialIndex, static_cast<MaterialSlot>(slots_used.size()));
      if (fresh) {
        if (slots_used.size() >= kMaxMaterialsPerMesh)
          throw MeshIoError(quoted(path) + ": more than " + std::to_string(kMaxMaterialsPerMesh) + " materials");
        slots_used.push_back(m.mMaterialIndex);
      }
      slot = it->second;
    }
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
        if (materials) join.out.face_material.push_back(slot);
      } else {  // aiProcess_Triangulate leaves nothing larger; refuse rather than drop if it ever does
        throw MeshIoError(quoted(path) + ": a face of " + std::to_string(face.mNumIndices) +
                          " corners was not triangulated");
      }
    }
  }
  if (!result.parts.empty()) {
    MeshPart& last = result.parts.back();
    last.vertex_count = static_cast<std::uint32_t>(join.out.positions.size()) - last.first_vertex;
    last.triangle_count = static_cast<std::uint32_t>(join.out.triangles.size()) - last.first_triangle;
    // Nodes that only held points or lines are no parts.
    std::erase_if(result.parts, [](const MeshPart& p) { return p.triangle_count == 0; });
    if (result.parts.size() < 2) result.parts.clear();
  }
  report.faces = join.out.triangles.size();
  if (join.out.triangles.empty()) {
    throw MeshIoError(quoted(path) + ": empty mesh (no triangles): only " + std::to_string(report.ignored_points) +
                      " points and " + std::to_string(report.ignored_lines) + " lines (trispline loads surfaces)");
  }
  if (materials) {
    result.materials = convert_assimp_materials(*scene, slots_used, path);
    if (!result.materials) join.out.face_material.clear();
  }
  result.mesh = std::move(join.out);
  return result;
}

}  // namespace trispline::core
