#include "core/mesh/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <string>

#include "core/mesh/path_quote.h"

namespace trispline::core {
namespace {

std::string lower_ext(const std::filesystem::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

}  // namespace

void write_image_rgba8(const std::filesystem::path& path, int width, int height,
                       const std::vector<unsigned char>& rgba) {
  namespace OIIO = OIIO_NAMESPACE;
  const std::string ext = lower_ext(path);
  if (ext != ".png" && ext != ".exr")
    throw ImageIoError(quoted(path) + ": unsupported image extension '" + ext + "' (supported: .png .exr)");
  if (width < 1 || height < 1 || rgba.size() != static_cast<std::size_t>(width) * height * 4)
    throw ImageIoError(quoted(path) + ": image of " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                       std::to_string(std::max(0, width) * std::max(0, height) * 4) + " bytes, got " +
                       std::to_string(rgba.size()));
  // The temporary keeps the real extension last so OpenImageIO picks the right writer.
  const std::filesystem::path tmp = path.parent_path() / (path.stem().string() + ".tmp" + ext);
  auto out = OIIO::ImageOutput::create(tmp.string());
  if (!out) throw ImageIoError(quoted(path) + ": no image writer: " + OIIO::geterror());
  OIIO::ImageSpec spec(width, height, 4, ext == ".exr" ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  bool ok = out->open(tmp.string(), spec);
  ok = ok && out->write_image(OIIO::TypeDesc::UINT8, rgba.data());
  const std::string err = ok ? std::string() : out->geterror();
  ok = out->close() && ok;
  if (!ok) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw ImageIoError(quoted(path) + ": cannot write image: " + (err.empty() ? out->geterror() : err));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw ImageIoError(quoted(path) + ": cannot rename temporary file: " + ec.message());
  }
}

ImageRgba8 read_image_rgba8(const std::filesystem::path& path) {
  namespace OIIO = OIIO_NAMESPACE;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw ImageIoError(quoted(path) + ": file not found");
  // Keep alpha unassociated (as PNG stores it); by default OpenImageIO premultiplies on read.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path.string(), &config);
  if (!in) throw ImageIoError(quoted(path) + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  if (w < 1 || h < 1 || nc < 1) throw ImageIoError(quoted(path) + ": image has no pixels");
  std::vector<unsigned char> src(static_cast<std::size_t>(w) * h * nc);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::UINT8, src.data())) {
    const std::string err = in->geterror();
    throw ImageIoError(quoted(path) + ": cannot decode image: " + err);
  }
  in->close();
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
