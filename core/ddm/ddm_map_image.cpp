#include "core/ddm/ddm_map_image.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace trispline::core {

namespace {

unsigned char to_byte(double t) { return static_cast<unsigned char>(std::lround(std::clamp(t, 0.0, 1.0) * 255.0)); }

}  // namespace

DdmMapImage ddm_map_image(const DdmMaps& maps, DdmMapQuantity what) {
  const int slots = maps.slot_count();
  if (slots <= 0) throw std::invalid_argument("maps: the layer holds no sampled chart");
  const int ru = maps.resolution.x, rv = maps.resolution.y;
  const std::size_t per_slot = maps.samples_per_slot();
  if (ru < 2 || rv < 2) throw std::invalid_argument("maps: a resolution below 2 samples per axis");
  DdmMapImage img;
  img.columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(slots))));
  img.rows = (slots + img.columns - 1) / img.columns;
  const std::size_t pixels = static_cast<std::size_t>(img.columns) * ru * static_cast<std::size_t>(img.rows) * rv;
  if (pixels > kMaxDdmMapImagePixels)
    throw std::invalid_argument("maps: " + std::to_string(slots) + " charts of " + std::to_string(ru) + " × " +
                                std::to_string(rv) + " samples make a " + std::to_string(pixels) +
                                "-pixel picture, over the " + std::to_string(kMaxDdmMapImagePixels) + " allowed");
  if (maps.samples.size() != static_cast<std::size_t>(slots) * per_slot * DdmMaps::kFloatsPerSample ||
      (!maps.valid.empty() && maps.valid.size() != static_cast<std::size_t>(slots) * per_slot))
    throw std::invalid_argument("maps: the samples do not match the maps' resolution");
  img.width = img.columns * ru;
  img.height = img.rows * rv;
  const auto valid = [&](int slot, int i, int j) {
    return maps.valid.empty() || maps.valid[(static_cast<std::size_t>(slot) * rv + j) * ru + i] != 0;
  };
  // The positions' box: over the surface samples (filled ones repeat their neighbours' values).
  glm::dvec3 lo(1e300), hi(-1e300);
  for (int s = 0; s < slots; ++s)
    for (int j = 0; j < rv; ++j)
      for (int i = 0; i < ru; ++i)
        if (valid(s, i, j)) {
          const float* f = maps.sample(s, i, j);
          const glm::dvec3 p(f[0], f[1], f[2]);
          lo = glm::min(lo, p), hi = glm::max(hi, p);
        }
  const glm::dvec3 span = glm::max(hi - lo, glm::dvec3(1e-300));
  img.rgba.assign(pixels * 4, 0);
  for (int s = 0; s < slots; ++s) {
    const int x0 = (s % img.columns) * ru, y0 = (s / img.columns) * rv;
    for (int j = 0; j < rv; ++j)
      for (int i = 0; i < ru; ++i) {
        const float* f = maps.sample(s, i, j);
        const glm::dvec3 c = what == DdmMapQuantity::positions ? (glm::dvec3(f[0], f[1], f[2]) - lo) / span
                                                               : 0.5 * (glm::dvec3(f[3], f[4], f[5]) + glm::dvec3(1.0));
        unsigned char* px = &img.rgba[((static_cast<std::size_t>(y0) + (rv - 1 - j)) * img.width + x0 + i) * 4];
        px[0] = to_byte(c.x), px[1] = to_byte(c.y), px[2] = to_byte(c.z);
        px[3] = valid(s, i, j) ? 255 : kDdmMapFilledAlpha;
      }
  }
  return img;
}

}  // namespace trispline::core
