// The file a file-reading fuzz target hands its reader: the input written to "<tmp>/<prefix>_<pid>/input<ext>" (one
// folder per process, the same file for every input, so readers see a real path with the right extension).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace trispline::fuzz {

// Writes `size` bytes to the target's input file and returns its path, or an empty path when it cannot be written.
inline std::filesystem::path write_input_file(const char* prefix, const char* ext, const std::uint8_t* data,
                                              std::size_t size) {
  static const std::filesystem::path file = [&] {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / (std::string(prefix) + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir / (std::string("input") + ext);
  }();
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) return {};
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  return file;
}

}  // namespace trispline::fuzz
