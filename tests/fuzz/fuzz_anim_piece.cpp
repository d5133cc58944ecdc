// libFuzzer target: an animation piece's reader (core/mesh/gltf_anim_io.h read_piece), what `trispline farm
// assemble` runs on each chunk's animation.piece of a farm folder someone else wrote. Any input must either give a
// builder or throw MeshIoError; any other exception, a crash, an allocation past the input's size or a hang is a
// finding. An accepted piece must write itself and read back, and write its animation.glb.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/mesh/gltf_anim_io.h"
#include "core/mesh/mesh_io.h"

using namespace trispline;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d = std::filesystem::temp_directory_path() / ("fuzz_anim_piece_" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::filesystem::path in = dir / "in.piece";
  std::ofstream(in, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    const core::MorphAnimationBuilder piece = core::MorphAnimationBuilder::read_piece(in);
    piece.write_piece(dir / "again.piece");
    core::MorphAnimationBuilder::read_piece(dir / "again.piece");  // what the farm writes, it must read
    piece.write_glb(dir / "animation.glb");
  } catch (const core::MeshIoError&) {
  }
  return 0;
}
