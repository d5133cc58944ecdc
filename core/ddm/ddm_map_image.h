// trispline::core::ddm_map_image — a layer's sampled position or normal map as a picture, the seed's Figs. 5.3 (the
// teapot body's P and N maps, §5.3.1) and 5.5 (a polygonal model's maps with their invalid texels filled, §5.4.1).
//
// The maps (ddm_pn_maps.h) hold one R_u × R_v grid of samples per sampled chart ("slot"). The picture tiles the slots
// in a grid of ⌈√#slots⌉ columns, slot 0 at the top left, each with u to the right and v upwards (sample row R_v − 1
// on top), one pixel per sample:
//   positions  each coordinate mapped linearly from the bounding box of the surface samples (lo → 0, hi → 255), so
//              x, y, z read as red, green, blue (Fig. 5.3(a));
//   normals    (n + 1) / 2 per component (Fig. 5.3(b)).
// Alpha is 255 where the sample lies on the surface and kDdmMapFilledAlpha where the diffusion fill of a UV-mapped
// base put it (the seed's validity channel, Fig. 5.5); pixels of the grid that no slot covers are transparent black.
#pragma once

#include <cstdint>
#include <vector>

#include "core/ddm/ddm_pn_maps.h"

namespace trispline::core {

enum class DdmMapQuantity { positions, normals };

inline constexpr unsigned char kDdmMapFilledAlpha = 96;
inline constexpr std::size_t kMaxDdmMapImagePixels = std::size_t(1) << 26;  // 64 Mpx (256 MiB of RGBA)

struct DdmMapImage {
  int width = 0, height = 0;        // pixels
  int columns = 1, rows = 1;        // slots across and down
  std::vector<unsigned char> rgba;  // #(width·height) × 4, top row first, unassociated alpha
};

// The picture of `maps` described above. Throws std::invalid_argument when the maps hold no slot, their samples do not
// match their resolution, or the picture would exceed kMaxDdmMapImagePixels (checked before allocating).
DdmMapImage ddm_map_image(const DdmMaps& maps, DdmMapQuantity what);

}  // namespace trispline::core
