// Loading the OpenImageIO plugin on first use. See image_codec.h.
#include "core/image/image_codec.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <string>
#include <system_error>

#include "core/image/image_io.h"

#ifndef TRISPLINE_CODEC_BUILD_DIR
#error "TRISPLINE_CODEC_BUILD_DIR: the folder the build writes libtrispline_oiio.so to (core/mesh/CMakeLists.txt)"
#endif

namespace trispline::core {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPluginFile = "libtrispline_oiio.so";
constexpr const char* kEntryPoint = "trispline_image_codec";  // extern "C" const ImageCodec* (void)

const ImageCodec* load_plugin() {
  std::vector<fs::path> tried;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) tried.push_back(self.parent_path().parent_path() / "lib" / "trispline" / kPluginFile);
  tried.push_back(fs::path(TRISPLINE_CODEC_BUILD_DIR) / kPluginFile);
  std::string why;
  for (const fs::path& p : tried) {
    if (!fs::is_regular_file(p, ec)) continue;
    void* handle = ::dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed: the codec lives as long as the process
    if (!handle) {
      const char* e = ::dlerror();
      why += "; " + p.string() + ": " + (e ? e : "dlopen failed");
      continue;
    }
    using Entry = const ImageCodec* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(handle, kEntryPoint));
    if (const ImageCodec* codec = entry ? entry() : nullptr) return codec;
    why += "; " + p.string() + ": no " + kEntryPoint;
  }
  std::string paths;
  for (const fs::path& p : tried) paths += (paths.empty() ? "" : ", ") + p.string();
  throw ImageIoError("cannot load the image codec (OpenImageIO plugin " + std::string(kPluginFile) + "; looked in " +
                     paths + why + ")");
}

}  // namespace

const ImageCodec& image_codec() {
  static std::mutex mutex;
  static const ImageCodec* codec = nullptr;
  std::lock_guard<std::mutex> lock(mutex);
  if (!codec) codec = load_plugin();
  return *codec;
}

}  // namespace trispline::core
