#include "core/image/image_io.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "core/base/text.h"
#include "core/image/image_codec.h"

namespace trispline::core {

namespace {

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

}  // namespace

void write_image_rgba8(const std::filesystem::path& path, int width, int height,
                       const std::vector<unsigned char>& rgba) {
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".exr")
    throw ImageIoError(quoted(path) + ": unsupported image extension '" + ext + "' (supported: .png .exr)");
  if (width < 1 || height < 1 || rgba.size() != static_cast<std::size_t>(width) * height * 4)
    throw ImageIoError(quoted(path) + ": image of " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                       std::to_string(std::max(0, width) * std::max(0, height) * 4) + " bytes, got " +
                       std::to_string(rgba.size()));
  // The temporary keeps the real extension last so OpenImageIO picks the right writer.
  const std::filesystem::path tmp = path.parent_path() / (path.stem().string() + ".tmp" + ext);
  ImageWriteSpec spec;
  spec.width = width;
  spec.height = height;
  spec.stored = ext == ".exr" ? PixelType::kHalf : PixelType::kUint8;
  spec.int_attributes = {{"oiio:UnassociatedAlpha", 1}};
  const std::string err = image_codec().write_file(tmp.string(), spec, PixelType::kUint8, rgba.data());
  if (!err.empty()) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw ImageIoError(quoted(path) + ": cannot write image: " + err);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw ImageIoError(quoted(path) + ": cannot rename temporary file: " + ec.message());
  }
}

ImageRgba8 read_image_rgba8(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw ImageIoError(quoted(path) + ": file not found");
  // Keep alpha unassociated (as PNG stores it); by default OpenImageIO premultiplies on read.
  std::string err;
  auto in = image_codec().open_file(path.string(), true, err);
  if (!in) throw ImageIoError(quoted(path) + ": cannot read image: " + err);
  const ImageHeader& spec = in->header();
  if (spec.width < 1 || spec.height < 1 || spec.channels < 1)
    throw ImageIoError(quoted(path) + ": image has no pixels");
  const int w = static_cast<int>(spec.width), h = static_cast<int>(spec.height), nc = spec.channels;
  std::vector<unsigned char> src(static_cast<std::size_t>(w) * h * nc);
  if (!in->read_uint8(nc, src.data())) throw ImageIoError(quoted(path) + ": cannot decode image: " + in->error());
  in.reset();
  ImageRgba8 img;
  img.width = w;
  img.height = h;
  img.rgba.resize(static_cast<std::size_t>(w) * h * 4);
  for (std::size_t i = 0; i < static_cast<std::size_t>(w) * h; ++i) {
    const unsigned char* s = &src[i * nc];
    unsigned char* d = &img.rgba[i * 4];
    if (nc >= 3) {
      d[0] = s[0], d[1] = s[1], d[2] = s[2];
    } else {
      d[0] = d[1] = d[2] = s[0];
    }
    d[3] = nc == 4 ? s[3] : nc == 2 ? s[1] : 255;
  }
  return img;
}

}  // namespace trispline::core
