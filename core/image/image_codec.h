// trispline::core image codec: the OpenImageIO calls of trispline behind one interface, implemented in a plugin
// (libtrispline_oiio.so, core/image/oiio_codec.cpp) that is loaded on the first image read or write.
//
// Why a plugin: Debian's OpenImageIO maps ~260 shared libraries (OpenCV, GDAL, libheif, FFmpeg, …), ~0.45 s of CPU
// at every process start (0.75 s under ASan). Most trispline processes never touch an image — `farm status`, a
// refused command line, a replay without frames, most test executables — and now start without it.
//
//   image_codec()            the codec; loads the plugin on the first call (thread-safe)
//   ImageCodec::open_file    a reader of an image file (any format OpenImageIO reads; first subimage)
//   ImageCodec::open_memory  a reader of encoded bytes in memory, its format told by an extension (".png")
//   ImageCodec::write_file   a file in the format of its extension, written in one go
//   ImageCodec::encode       encoded bytes in memory in the format of an extension
// The files and bytes are OpenImageIO's; callers (image_io.h, material_image.h, editor/replay/record.h, the farm's
// frame checks) keep their own size budgets and error messages. Errors cross the plugin boundary as strings, never as
// exceptions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace trispline::core {

// Pixel types of the files and of the caller's buffers (OpenImageIO's TypeDesc::UINT8 / HALF / FLOAT).
enum class PixelType { kUint8, kHalf, kFloat };

// What an image header says: pixels, channels, depth (> 1 for volume images, which trispline refuses).
struct ImageHeader {
  long long width = 0, height = 0;  // pixels
  int channels = 0;
  long long depth = 1;
};

// An opened image. Reads convert to the caller's type (integers scaled to [0,1] for floats, floats clamped to
// [0,1]·255 for 8-bit, no colour conversion).
class ImageReader {
 public:
  virtual ~ImageReader() = default;
  virtual const ImageHeader& header() const = 0;
  // Reads channels [0, channels) of every pixel as 8-bit, rows top to bottom, into `dst` (#(width·height·channels)
  // bytes). False on a decoding error (error() says which).
  virtual bool read_uint8(int channels, std::uint8_t* dst) = 0;
  // Reads row `y` (every channel) as floats into `dst` (#(width·channels) floats). False on a decoding error.
  virtual bool read_row_float(int y, float* dst) = 0;
  virtual std::string error() = 0;
};

// What a write stores: width × height pixels of `channels` channels as `stored`, with string attributes
// (OpenImageIO's names: "compression" = "zip", "DateTime" = "" for reproducible EXRs) and integer ones
// ("oiio:UnassociatedAlpha" = 1: the pixels' alpha is straight, as PNG stores it).
struct ImageWriteSpec {
  int width = 0, height = 0, channels = 4;
  PixelType stored = PixelType::kUint8;
  std::vector<std::pair<std::string, std::string>> text_attributes;
  std::vector<std::pair<std::string, int>> int_attributes;
};

class ImageCodec {
 public:
  virtual ~ImageCodec() = default;
  // Opens `file` (alpha kept unassociated when `unassociated_alpha`). nullptr with `error` set when it cannot be read.
  virtual std::unique_ptr<ImageReader> open_file(const std::string& file, bool unassociated_alpha,
                                                 std::string& error) const = 0;
  // Opens `size` encoded bytes (not copied: they must outlive the reader) in the format of `extension` (".png",
  // ".jpg", ".exr", …), alpha unassociated. nullptr with `error` set when they cannot be read.
  virtual std::unique_ptr<ImageReader> open_memory(const std::uint8_t* bytes, std::size_t size,
                                                   const std::string& extension, std::string& error) const = 0;
  // Writes `pixels` (#(width·height·channels) values of `given`, rows top to bottom) to `file`, whose extension
  // picks the format. "" on success, else the error; a failed write may leave a partial file (callers write to a
  // temporary and rename).
  virtual std::string write_file(const std::string& file, const ImageWriteSpec& spec, PixelType given,
                                 const void* pixels) const = 0;
  // Encodes like write_file into `out` (replaced), in the format of `extension`. "" on success, else the error.
  virtual std::string encode(std::vector<std::uint8_t>& out, const std::string& extension, const ImageWriteSpec& spec,
                             PixelType given, const void* pixels) const = 0;
};

// The codec of this process: the plugin is looked for beside the executable's ../lib/trispline (an installed tree),
// then in the build tree that compiled this file. Throws ImageIoError (core/image/image_io.h) naming the paths tried
// and dlerror()'s message when it cannot be loaded; later calls retry.
const ImageCodec& image_codec();

}  // namespace trispline::core
