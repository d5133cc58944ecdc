// Material images through OpenImageIO (image_codec.h), in memory. See material_image.h.
#include "core/mesh/material_image.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "core/base/text.h"
#include "core/image/image_codec.h"

namespace trispline::core {
namespace {

bool starts_with(const std::vector<std::uint8_t>& b, std::initializer_list<int> magic) {
  if (b.size() < magic.size()) return false;
  std::size_t i = 0;
  for (int m : magic)
    if (b[i++] != static_cast<std::uint8_t>(m)) return false;
  return true;
}

// The extension OpenImageIO chooses its reader by, from a MIME type.
std::string extension_of_mime(const std::string& mime) {
  const std::string m = ascii_lower(mime);
  if (m == "image/png") return ".png";
  if (m == "image/jpeg" || m == "image/jpg") return ".jpg";
  if (m == "image/bmp" || m == "image/x-bmp") return ".bmp";
  if (m == "image/tiff") return ".tif";
  if (m == "image/x-exr" || m == "image/aces") return ".exr";
  if (m == "image/x-tga" || m == "image/tga" || m == "image/x-targa") return ".tga";
  return "";
}

std::string mime_of_extension(const std::string& ext) {
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  if (ext == ".bmp") return "image/bmp";
  if (ext == ".tif" || ext == ".tiff") return "image/tiff";
  if (ext == ".exr") return "image/x-exr";
  if (ext == ".tga") return "image/x-tga";
  return "";
}

// "PNG", "JPEG", ... for messages.
std::string format_of_extension(const std::string& ext) {
  if (ext == ".jpg") return "JPEG";
  if (ext == ".tif") return "TIFF";
  std::string f = ext.substr(1);
  std::transform(f.begin(), f.end(), f.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return f;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  int u = 0;
  while (bytes >= 1024 && u < 4) bytes /= 1024, ++u;
  char buf[64];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
  return buf;
}

}  // namespace

std::string sniff_image_mime(const std::vector<std::uint8_t>& b) {
  if (starts_with(b, {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) return "image/png";
  if (starts_with(b, {0xFF, 0xD8, 0xFF})) return "image/jpeg";
  if (starts_with(b, {'B', 'M'})) return "image/bmp";
  if (starts_with(b, {'I', 'I', 0x2A, 0x00}) || starts_with(b, {'M', 'M', 0x00, 0x2A})) return "image/tiff";
  if (starts_with(b, {0x76, 0x2F, 0x31, 0x01})) return "image/x-exr";
  return "";
}

MaterialImage decode_material_image(std::vector<std::uint8_t> encoded, const std::string& mime_type,
                                    const std::string& name, const std::string& uri, std::uint64_t max_bytes) {
  MaterialImage img;
  img.name = name;
  img.uri = uri;
  std::string mime = sniff_image_mime(encoded);
  if (mime.empty()) mime = extension_of_mime(mime_type).empty() ? "" : ascii_lower(mime_type);
  if (mime.empty()) mime = mime_of_extension(lower_extension(uri));
  img.mime_type = mime.empty() ? mime_type : mime;
  img.encoded = std::move(encoded);
  if (img.encoded.empty()) {
    img.error = "the image has no bytes";
    return img;
  }
  const std::string ext = extension_of_mime(mime);
  if (ext.empty()) {
    img.error = "unknown image format (not PNG, JPEG, TGA, EXR, TIFF or BMP)";
    return img;
  }
  const std::string format = format_of_extension(ext);
  std::string err;
  const ImageCodec* codec = nullptr;
  try {
    codec = &image_codec();
  } catch (const std::exception& e) {  // an installation without the plugin: the texture is left out, as unreadable
    img.error = e.what();
    return img;
  }
  auto in = codec->open_memory(img.encoded.data(), img.encoded.size(), ext, err);
  if (!in) {
    img.error = "cannot decode " + format + ": " + err;
    return img;
  }
  const ImageHeader spec = in->header();
  const long long w = spec.width, h = spec.height;
  const int nc = spec.channels;
  if (w < 1 || h < 1 || nc < 1 || spec.depth > 1) {
    img.error = format + " image has no pixels (" + std::to_string(w) + " × " + std::to_string(h) + ")";
    return img;
  }
  const double need = double(w) * double(h) * 4.0;
  if (w > kMaxMaterialImageSide || h > kMaxMaterialImageSide || need > double(max_bytes)) {
    img.error = format + " image of " + std::to_string(w) + " × " + std::to_string(h) + " pixels needs " +
                format_bytes(need) + " decoded, over the " + format_bytes(double(max_bytes)) + " limit (and " +
                std::to_string(kMaxMaterialImageSide) + " pixels a side) for texture images";
    return img;
  }
  const int used = std::min(nc, 4);
  const std::size_t pixels = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<std::uint8_t> src(pixels * used);
  if (!in->read_uint8(used, src.data())) {
    img.error = "cannot decode " + format + ": " + in->error();
    return img;
  }
  in.reset();
  img.rgba8.resize(pixels * 4);
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint8_t* s = &src[i * used];
    std::uint8_t* d = &img.rgba8[i * 4];
    if (used >= 3) {
      d[0] = s[0], d[1] = s[1], d[2] = s[2];
    } else {
      d[0] = d[1] = d[2] = s[0];
    }
    d[3] = used == 4 ? s[3] : used == 2 ? s[1] : 255;
  }
  img.width = static_cast<int>(w);
  img.height = static_cast<int>(h);
  return img;
}

std::vector<std::uint8_t> encode_png_rgba8(int width, int height, const std::vector<std::uint8_t>& rgba) {
  if (width < 1 || height < 1 || rgba.size() != static_cast<std::size_t>(width) * height * 4)
    throw std::runtime_error("encode_png_rgba8: " + std::to_string(rgba.size()) + " bytes for " +
                             std::to_string(width) + " × " + std::to_string(height) + " RGBA pixels");
  ImageWriteSpec spec;
  spec.width = width;
  spec.height = height;
  spec.int_attributes = {{"oiio:UnassociatedAlpha", 1}};
  std::vector<std::uint8_t> out;
  const std::string err = image_codec().encode(out, ".png", spec, PixelType::kUint8, rgba.data());
  if (!err.empty()) throw std::runtime_error("cannot encode PNG: " + err);
  return out;
}

std::pair<std::vector<std::uint8_t>, std::string> gltf_image_bytes(const MaterialImage& image) {
  if (!image.readable()) return {};
  const std::string mime = sniff_image_mime(image.encoded);
  if (mime == "image/png" || mime == "image/jpeg") return {image.encoded, mime};
  return {encode_png_rgba8(image.width, image.height, image.rgba8), "image/png"};
}

}  // namespace trispline::core
