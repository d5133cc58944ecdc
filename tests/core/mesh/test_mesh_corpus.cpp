// Every mesh file of a corpus the project does not ship (assets/data/corpus/: CGAL's data meshes, assimp's own test
// models, Geomview's samples; fetched by scripts/fetch_assets.sh from Debian packages) loads all its faces or is
// refused with a MeshIoError naming the file — never partially, never with another exception. "All its faces" is
// the count the reference loader prints: `assimp info FILE -tri` (assimp-utils: its import, then triangulation only).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/mesh/mesh_io.h"
#include "core/mesh/model_load.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

fs::path corpus_dir() { return fs::path(TRISPLINE_SOURCE_DIR) / "assets" / "data" / "corpus"; }

std::vector<fs::path> corpus_files() {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(corpus_dir())) {
    if (!e.is_regular_file()) continue;
    const std::string ext = core::lower_extension(e.path());
    if (ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// `assimp info FILE -tri`: the number of faces (all primitive types) after assimp's triangulation, or -1 when assimp
// cannot import the file.
struct Reference {
  long long faces = -1;
  std::string types;
};
// OFF allows '#' comments anywhere and blank lines, which assimp's reader only skips before the header; assimp 5.2
// loses the faces of UTF-16 BE text. The reference reads a copy with comments and blank lines removed (regexes here,
// not the loader's code) or converted to UTF-8 by the iconv program.
Reference assimp_reference(const fs::path& original) {
  fs::path file = original;
  if (core::lower_extension(file) == ".off") {
    std::ifstream in(original, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    file = fs::temp_directory_path() / ("trispline_corpus_ref_" + std::to_string(::getpid()) + ".off");
    const std::string no_comments = std::regex_replace(text.str(), std::regex("#[^\\n]*"), "");
    std::ofstream(file, std::ios::binary) << std::regex_replace(no_comments, std::regex("\\n[ \\t\\r]*(?=\\n)"), "");
  }
  std::ifstream head(original, std::ios::binary);
  unsigned char bom[2] = {};
  head.read(reinterpret_cast<char*>(bom), 2);
  if ((bom[0] == 0xFE && bom[1] == 0xFF) || (bom[0] == 0xFF && bom[1] == 0xFE)) {  // assimp 5.2 mis-converts UTF-16
    file = fs::temp_directory_path() /
           ("trispline_corpus_ref_" + std::to_string(::getpid()) + core::lower_extension(original));
    const std::string conv = "iconv -f UTF-16 -t UTF-8 '" + original.string() + "' > '" + file.string() + "'";
    if (std::system(conv.c_str()) != 0) return {};
  }
  const std::string cmd = "timeout 120 assimp info '" + file.string() + "' -tri 2>&1";
  Reference ref;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return ref;
  std::array<char, 4096> buf{};
  std::string out;
  while (std::fgets(buf.data(), buf.size(), p)) out += buf.data();
  ::pclose(p);
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("Faces:", 0) == 0) ref.faces = std::stoll(line.substr(6));
    if (line.rfind("Primitive Types:", 0) == 0) ref.types = line.substr(16);
  }
  if (out.find("ERROR") != std::string::npos) ref.faces = -1;
  return ref;
}

std::string short_name(const fs::path& p) { return fs::relative(p, corpus_dir()).string(); }

}  // namespace

TEST(MeshCorpus, EveryFileLoadsAllItsFacesOrIsRefusedClearly) {
  const std::vector<fs::path> files = corpus_files();
  ASSERT_GE(files.size(), 100u) << "the corpus is incomplete: run scripts/fetch_assets.sh";
  int loaded = 0, refused = 0;
  std::map<std::string, int> reasons;
  for (const fs::path& file : files) {
    SCOPED_TRACE(short_name(file));
    const Reference ref = assimp_reference(file);
    core::MeshLoadReport report;
    try {
      const core::TriMesh m = core::load_mesh(file, {}, &report);
      ++loaded;
      EXPECT_EQ(report.faces, m.triangles.size());
      EXPECT_EQ(report.ignored_points + report.ignored_lines, 0u) << "loose geometry must be refused by default";
      EXPECT_GE(ref.faces, 0) << "loaded a file the reference loader refuses";
      if (ref.faces >= 0) {
        EXPECT_EQ(static_cast<long long>(m.triangles.size() + report.duplicate_faces), ref.faces)
            << "faces lost or invented (" << ref.types << ")";
        if (report.duplicate_faces)
          std::printf("%s: %zu repeated triangles removed\n", short_name(file).c_str(), report.duplicate_faces);
      }
      EXPECT_EQ(m.normals.size(), m.positions.size());
    } catch (const core::MeshIoError& e) {
      ++refused;
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind("'" + file.string() + "': ", 0), 0u) << "the error must name the file: " << msg;
      EXPECT_GT(msg.size(), file.string().size() + 8) << "the error must say why: " << msg;
      // Group by reason for the summary (the text after the file name, numbers dropped).
      std::string why = msg.substr(file.string().size() + 4);
      why.erase(std::remove_if(why.begin(), why.end(), [](char c) { return c >= '0' && c <= '9'; }), why.end());
      ++reasons[why.substr(0, 70)];
      std::printf("refused %s: %s\n", short_name(file).c_str(), msg.substr(file.string().size() + 4).c_str());
      // With loose geometry allowed, such a file loads its faces and the counts add up to the reference.
      if (msg.find("loose geometry") != std::string::npos) {
        core::MeshLoadOptions options;
        options.ignore_loose = true;
        const core::TriMesh m = core::load_mesh(file, options, &report);
        EXPECT_EQ(static_cast<long long>(m.triangles.size() + report.duplicate_faces + report.ignored_points +
                                         report.ignored_lines),
                  ref.faces);
      }
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a MeshIoError: " << e.what();
    }
  }
  std::printf("corpus: %zu files, %d loaded whole, %d refused\n", files.size(), loaded, refused);
  for (const auto& [why, n] : reasons) std::printf("  %3d × %s\n", n, why.c_str());
}

// The files the old OpenMesh path loaded with 1–3 triangles (Geomview's per-face colour OFF files) load whole.
TEST(MeshCorpus, GeomviewColourFilesLoadWhole) {
  for (const char* name : {"facecube.off", "vertcube.off", "mushroom.off", "pieces/cube1.off", "br2.off"}) {
    const fs::path file = corpus_dir() / "geomview" / "geom" / name;
    SCOPED_TRACE(name);
    ASSERT_TRUE(fs::exists(file));
    const core::TriMesh m = core::load_mesh(file);
    EXPECT_EQ(static_cast<long long>(m.triangles.size()), assimp_reference(file).faces);
    EXPECT_GE(m.triangles.size(), 4u);
  }
}

// Formats without materials (OFF, PLY, STL): assimp makes one up (unnamed grey for OFF and PLY, "DefaultMaterial" for
// STL); none is the file's, so the model has no MaterialSet and the object keeps the colour its line gives.
TEST(MeshCorpus, FormatsWithoutMaterialsLeaveTheObjectsColour) {
  for (const fs::path& file : {corpus_dir() / "cgal" / "camel.off", corpus_dir() / "assimp" / "PLY" / "cube.ply",
                               corpus_dir() / "assimp" / "STL" / "Wuson.stl"}) {
    SCOPED_TRACE(file.filename().string());
    ASSERT_TRUE(fs::exists(file));
    const core::LoadedModel m = core::load_model(file);
    EXPECT_GT(m.mesh.triangle_count(), 0u);
    EXPECT_FALSE(m.materials) << "a material the file does not have";
  }
}
