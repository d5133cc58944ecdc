// The OpenImageIO plugin (libtrispline_oiio.so): ImageCodec (image_codec.h) over OpenImageIO's ImageInput and
// ImageOutput. Loaded by image_codec() on the first image read or write; it links nothing of trispline.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "core/image/image_codec.h"

namespace trispline::core {
namespace {

namespace OIIO = OIIO_NAMESPACE;

OIIO::TypeDesc type_of(PixelType t) {
  switch (t) {
    case PixelType::kUint8:
      return OIIO::TypeDesc::UINT8;
    case PixelType::kHalf:
      return OIIO::TypeDesc::HALF;
    case PixelType::kFloat:
      return OIIO::TypeDesc::FLOAT;
  }
  return OIIO::TypeDesc::UINT8;
}

class OiioReader final : public ImageReader {
 public:
  // `proxy` (null for files) must outlive `in`: it is declared first, so it is destroyed last.
  OiioReader(std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy, std::unique_ptr<OIIO::ImageInput> in)
      : proxy_(std::move(proxy)), in_(std::move(in)) {
    const OIIO::ImageSpec& spec = in_->spec();
    header_.width = spec.width;
    header_.height = spec.height;
    header_.channels = spec.nchannels;
    header_.depth = spec.depth;
  }
  ~OiioReader() override { in_->close(); }
  const ImageHeader& header() const override { return header_; }
  bool read_uint8(int channels, std::uint8_t* dst) override {
    return in_->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, dst);
  }
  bool read_row_float(int y, float* dst) override { return in_->read_scanline(y, 0, OIIO::TypeDesc::FLOAT, dst); }
  std::string error() override { return in_->geterror(); }

 private:
  std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy_;
  std::unique_ptr<OIIO::ImageInput> in_;
  ImageHeader header_;
};

OIIO::ImageSpec spec_of(const ImageWriteSpec& s) {
  OIIO::ImageSpec spec(s.width, s.height, s.channels, type_of(s.stored));
  for (const auto& [name, value] : s.text_attributes) spec.attribute(name, value);
  for (const auto& [name, value] : s.int_attributes) spec.attribute(name, value);
  return spec;
}

// Opens, writes and closes `out` (named `name`, whose extension picks the format). "" or the error.
std::string write_with(OIIO::ImageOutput& out, const std::string& name, const ImageWriteSpec& s, PixelType given,
                       const void* pixels) {
  bool ok = out.open(name, spec_of(s));
  ok = ok && out.write_image(type_of(given), pixels);
  std::string err = ok ? std::string() : out.geterror();
  ok = out.close() && ok;
  if (!ok && err.empty()) err = out.geterror();
  if (!ok && err.empty()) err = "unknown OpenImageIO error";
  return ok ? std::string() : err;
}

class OiioCodec final : public ImageCodec {
 public:
  std::unique_ptr<ImageReader> open_file(const std::string& file, bool unassociated_alpha,
                                         std::string& error) const override {
    OIIO::ImageSpec config;
    if (unassociated_alpha) config.attribute("oiio:UnassociatedAlpha", 1);  // OpenImageIO premultiplies by default
    auto in = OIIO::ImageInput::open(file, &config);
    if (!in) {
      error = OIIO::geterror();
      return nullptr;
    }
    return std::make_unique<OiioReader>(nullptr, std::move(in));
  }

  std::unique_ptr<ImageReader> open_memory(const std::uint8_t* bytes, std::size_t size, const std::string& extension,
                                           std::string& error) const override {
    auto proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(const_cast<std::uint8_t*>(bytes), size);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    void* proxy_ptr = proxy.get();
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_ptr);  // read from memory, never from a file
    auto in = OIIO::ImageInput::open("image" + extension, &config);
    if (!in) {
      error = OIIO::geterror();
      return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(proxy), std::move(in));
  }

  std::string write_file(const std::string& file, const ImageWriteSpec& spec, PixelType given,
                         const void* pixels) const override {
    auto out = OIIO::ImageOutput::create(file);
    if (!out) return "no image writer: " + OIIO::geterror();
    return write_with(*out, file, spec, given, pixels);
  }

  std::string encode(std::vector<std::uint8_t>& out, const std::string& extension, const ImageWriteSpec& spec,
                     PixelType given, const void* pixels) const override {
    out.clear();
    OIIO::Filesystem::IOVecOutput proxy(out);
    const std::string name = "image" + extension;
    auto writer = OIIO::ImageOutput::create(name);
    if (!writer) return "no image writer: " + OIIO::geterror();
    writer->set_ioproxy(&proxy);
    return write_with(*writer, name, spec, given, pixels);
  }
};

}  // namespace
}  // namespace trispline::core

extern "C" __attribute__((visibility("default"))) const trispline::core::ImageCodec* trispline_image_codec() {
  static const trispline::core::OiioCodec codec;
  return &codec;
}
