// trispline::core image files (OpenImageIO): 8-bit RGBA in memory, PNG or EXR on disk (chosen by extension).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <vector>

namespace trispline::core {

class ImageIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ImageRgba8 {
  int width = 0, height = 0;        // pixels
  std::vector<unsigned char> rgba;  // #(width·height) × 4, top row first, unassociated alpha
};

// Writes .png (8-bit RGBA) or .exr (half float, values / 255, no colour conversion). Written to "<path>.tmp" then
// renamed. Throws ImageIoError on an unsupported extension, bad sizes (width, height ≥ 1,
// rgba.size() == width·height·4) or a failed write.
void write_image_rgba8(const std::filesystem::path& path, int width, int height,
                       const std::vector<unsigned char>& rgba);

// Reads any format OpenImageIO knows (first subimage), converted to 8-bit RGBA: grey → RGB, missing alpha → 255,
// float data clamped to [0,1]·255 with no colour conversion. Throws ImageIoError on a missing or unreadable file.
ImageRgba8 read_image_rgba8(const std::filesystem::path& path);

}  // namespace trispline::core
