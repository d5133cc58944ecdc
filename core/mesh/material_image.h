// trispline::core material images — encoded texture bytes ↔ MaterialImage (core/mesh/material.h), through
// OpenImageIO, in memory (no file is opened here: loaders read the bytes under their own folder rules).
//
//   decode_material_image  encoded bytes (PNG, JPEG, TGA, EXR, TIFF, BMP) → MaterialImage with 8-bit RGBA pixels
//   sniff_image_mime       the MIME type the first bytes announce ("" when unknown)
//   encode_png_rgba8       8-bit RGBA pixels → PNG bytes (glTF embeds only PNG and JPEG, glTF 2.0 §3.8.4)
//   gltf_image_bytes       what an export embeds for an image: its source bytes when PNG/JPEG, else PNG of rgba8
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/material.h"

namespace trispline::core {

// Largest decoded image (width × height × 4 bytes of rgba8): 512 MiB, e.g. 16384 × 8192. Decoding holds the file's
// own channels besides, at most as many bytes again for 8-bit sources.
inline constexpr std::uint64_t kMaxMaterialImageBytes = std::uint64_t(512) << 20;
// Largest side in pixels (OpenGL implementations offer 16384 at most; larger images are refused, not resampled).
inline constexpr int kMaxMaterialImageSide = 16384;

// Decodes `encoded` (the first subimage, first MIP level) to 8-bit RGBA, rows top to bottom: grey → grey in R, G, B;
// no alpha → 255; 16-bit and float data scaled to [0,255] (floats clamped to [0,1], no colour conversion); alpha
// unassociated. The format is told by the bytes (sniff_image_mime), else by `mime_type` ("image/png", ...), else by
// the extension of `uri`. The image's width × height × 4 is checked against `max_bytes` and each side against
// kMaxMaterialImageSide from the header alone, before any pixel is decoded.
// Never throws for bad input: on failure the result has `error` set ("cannot decode PNG: ...", "image of 100000 ×
// 100000 pixels needs 37.3 GiB decoded, over the 512 MiB limit for texture images"), empty `rgba8`, and keeps
// `name`, `uri`; `encoded` and `mime_type` are kept too when the bytes were read (export then leaves the texture out
// because the image is not readable()). On success `mime_type` is the sniffed type.
MaterialImage decode_material_image(std::vector<std::uint8_t> encoded, const std::string& mime_type,
                                    const std::string& name, const std::string& uri,
                                    std::uint64_t max_bytes = kMaxMaterialImageBytes);

// "image/png", "image/jpeg", "image/bmp", "image/tiff", "image/x-exr" from the magic bytes; "" otherwise (TGA has
// no magic number: it is told by mime type or extension).
std::string sniff_image_mime(const std::vector<std::uint8_t>& bytes);

// PNG file bytes of `rgba` (#(width·height) × 4, top row first, unassociated alpha). Throws std::runtime_error on
// bad sizes or an encoder failure.
std::vector<std::uint8_t> encode_png_rgba8(int width, int height, const std::vector<std::uint8_t>& rgba);

// (bytes, mime type) an export embeds for `image`: the source bytes unchanged when they are PNG or JPEG, else the
// decoded pixels encoded as PNG; ({}, "") when the image is not readable() (the material is written without it).
std::pair<std::vector<std::uint8_t>, std::string> gltf_image_bytes(const MaterialImage& image);

}  // namespace trispline::core
