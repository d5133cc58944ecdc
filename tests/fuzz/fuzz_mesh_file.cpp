// libFuzzer target: one mesh reader, the code Scene ▸ Load…, scene.load and ddm tiles run on files from anywhere.
// The extension is fixed per target (TRISPLINE_FUZZ_EXT: ".obj", ".ply", ".off", ".stl", ".gltf", ".glb"); the input
// is written to a file of that name in a folder of its own and loaded with load_mesh, then with "loose" ignored, and
// for glTF also as an animation clip (MeshClip::load). The contract under test: a file loads whole — a mesh that
// passes validate_mesh, with every position finite — or the reader throws MeshIoError (MeshClip::load: or
// std::invalid_argument, as documented). Any other exception, a
// signal, a sanitizer finding or a loaded mesh that breaks the contract aborts, which libFuzzer reports as a crash.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/mesh/mesh_clip.h"
#include "core/mesh/mesh_io.h"
#include "tests/fuzz/fuzz_input_file.h"

#ifndef TRISPLINE_FUZZ_EXT
#error "define TRISPLINE_FUZZ_EXT, e.g. \".obj\""
#endif

using namespace trispline;

namespace {

void check_loaded(const core::TriMesh& m, const core::MeshLoadReport& report) {
  try {
    core::validate_mesh(m, "fuzz");
  } catch (const core::MeshIoError& e) {
    std::fprintf(stderr, "load_mesh returned a mesh that fails validate_mesh: %s\n", e.what());
    std::abort();
  }
  if (m.normals.size() != m.positions.size() || report.faces != m.triangles.size()) {
    std::fprintf(stderr, "load_mesh: %zu normals for %zu vertices, report says %zu faces of %zu\n", m.normals.size(),
                 m.positions.size(), report.faces, m.triangles.size());
    std::abort();
  }
  for (const auto& n : m.normals)
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) {
      std::fprintf(stderr, "load_mesh returned a non-finite normal\n");
      std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = fuzz::write_input_file("trispline_fuzz_mesh", TRISPLINE_FUZZ_EXT, data, size);
  if (file.empty()) return 0;
  for (const bool ignore_loose : {false, true}) {
    core::MeshLoadOptions options;
    options.ignore_loose = ignore_loose;
    core::MeshLoadReport report;
    try {
      const core::TriMesh m = core::load_mesh(file, options, &report);
      check_loaded(m, report);
    } catch (const core::MeshIoError&) {
    }
  }
  const std::string ext = TRISPLINE_FUZZ_EXT;
  if (ext == ".gltf" || ext == ".glb") {
    try {  // MeshClip::load documents both: a bad file (MeshIoError) or a clip it cannot play (invalid_argument)
      core::MeshClip::load(file);
    } catch (const core::MeshIoError&) {
    } catch (const std::invalid_argument&) {
    }
  }
  return 0;
}
