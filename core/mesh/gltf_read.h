// trispline::core glTF reading rules — the one way core/mesh opens a .gltf/.glb (internal to core/mesh; load_mesh,
// read_gltf_objects, MeshClip and the animated-GLB readers all go through it). Rule: refuse before spending.
//
//   read_model       path → tinygltf::Model that passed every check below, or MeshIoError naming the file and reason
//   accessor_layout  where an accessor's elements are, after checking them against the actual bytes
//   read_accessor    accessor → #count × comps doubles, at most a caller-given number of elements
//   read_indices     index accessor → #count uint32
//   image_bytes      a data: URI or buffer view image's encoded bytes; external_image_bytes an image file's
//
// Checks, in order:
//   1. the file: a regular file (no directory, FIFO, device) of at most kMaxMeshFileBytes (file_check.h), read once;
//   2. its JSON (the .gltf text or the GLB's JSON chunk), streamed before tinygltf builds anything: nesting depth
//      ≤ kMaxGltfJsonDepth, values ≤ kMaxGltfJsonValues, Σ buffers' byteLength ≤ kMaxGltfBufferBytes, only the first
//      buffer of a GLB without a uri, buffer URIs relative paths without a scheme (data: URIs excepted);
//   3. external buffers (tinygltf::FsCallbacks): a URI must resolve (after "..", symlinks: weakly_canonical) inside
//      the folder of the glTF file (the folder as named, its own symlinks resolved) or below, to a regular file of at
//      most its buffer's byteLength; image files are not read here and images never decoded (data: URI images keep
//      their bytes in Image::image; external_image_bytes reads an image file under the same folder rule);
//   4. the model: every buffer view inside its buffer, every accessor (and sparse part) inside its buffer view with
//      overflow-safe arithmetic and a known component type and type, every index (mesh, node, skin, accessor, sampler,
//      scene) in range, nodes a forest (one parent at most, no cycle).
// What a reader decodes is bounded by the element limits the callers pass (kMaxMeshFile*, kMaxClipValues) and
// checked before anything is allocated.
#pragma once

#include <tiny_gltf.h>  // Debian's shared tinygltf: no configuration macros (see gltf_io.cpp)

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace trispline::core::gltf_read {

// Σ byteLength of all buffers of one file (GLB chunk, data: URIs, external files), bytes.
inline constexpr std::uintmax_t kMaxGltfBufferBytes = std::uintmax_t(2) << 30;
// JSON nesting: real files nest ~8 deep; tinygltf converts extras recursively.
inline constexpr int kMaxGltfJsonDepth = 64;
// JSON values (numbers, strings, arrays, objects, …): tinygltf's DOM and structs cost up to ~200 bytes a value.
inline constexpr std::size_t kMaxGltfJsonValues = 8'000'000;
// Vertices and triangles one file may yield, summed over every mesh node (a mesh used by n nodes counts n times).
// A loaded vertex costs ~200 bytes at peak (TriMesh in double, the per-object copy, decode buffers), so 20 M vertices
// stay within ~4 GB.
inline constexpr std::size_t kMaxMeshFileVertices = 20'000'000;
inline constexpr std::size_t kMaxMeshFileTriangles = 40'000'000;
// Numbers a MeshClip decodes or holds besides its vertices: morph deltas (6 per target and vertex), joints and
// weights, inverse bind matrices, sampler keys and values; 100 M doubles = 800 MB.
inline constexpr std::size_t kMaxClipValues = 100'000'000;

// Reads and checks `path` (see the header comment). Throws MeshIoError:
//   "'PATH': file not found" / "is a directory" / "… over the 2 GiB limit for mesh files"   (file_check.h)
//   "'PATH': cannot parse glTF file: <tinygltf's message>"
//   "'PATH': JSON nested deeper than 64 levels" / "JSON has more than 8000000 values"
//   "'PATH': buffer 0 URI '../x.bin' resolves to '/a/x.bin', outside the folder '/a/b' of the glTF file"
//   "'PATH': buffer 0 URI '/etc/passwd' is an absolute path; …" / "… URI 'p.bin': '/a/p.bin': is a FIFO …"
//   "'PATH': accessor 3 (count 300000000, 12-byte elements, stride 12) runs past the end of buffer view 0 (36 bytes)"
//   "'PATH': node 2 is a child of node 2 …" / "node 5 has two parents" / "nodes 0, 1 form a cycle" …
tinygltf::Model read_model(const std::filesystem::path& path);

// An accessor's elements: element i starts at data + i·stride (data == nullptr: no buffer view, all zeros). With
// sparse substitution: sparse_count pairs, index k at sparse_indices + k·index_size, values at sparse_values + k·elem.
struct AccessorLayout {
  const unsigned char* data = nullptr;
  std::size_t stride = 0, count = 0;
  int component_type = 0, component_size = 0, comps = 0;  // comps: 1 (SCALAR) … 16 (MAT4)
  bool normalized = false;
  std::size_t sparse_count = 0;
  const unsigned char* sparse_indices = nullptr;
  const unsigned char* sparse_values = nullptr;
  int sparse_index_type = 0;
};

// Layout of accessor `index` after checking it (range, types, views, bounds, sparse parts). `what` names its use in
// messages ("POSITION", "sampler input"). Throws MeshIoError "'PATH': <what> accessor …".
AccessorLayout accessor_layout(const tinygltf::Model& model, int index, const std::string& what,
                               const std::filesystem::path& path);

// Accessor `index` as #count × comps doubles: float, or (normalised) signed/unsigned byte/short and unsigned int
// (glTF 2.0 §3.6.2, §3.11 normalisation: signed max(c / max, −1)); `sparse` applies sparse substitution. Values are
// not checked for finiteness. Throws MeshIoError if the accessor does not have `comps` components or has more than
// `max_count` elements (checked before allocating), or as accessor_layout.
std::vector<double> read_accessor(const tinygltf::Model& model, int index, int comps, const std::string& what,
                                  const std::filesystem::path& path, std::size_t max_count, bool sparse = true);

// Index accessor `index` (SCALAR, unsigned byte/short/int, with a buffer view; sparse parts are not applied) as
// #count values. Throws MeshIoError as read_accessor.
std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index, const std::filesystem::path& path,
                                        std::size_t max_count);

// Largest texture image file read (external file, data: URI or buffer view alike), bytes.
inline constexpr std::uintmax_t kMaxImageFileBytes = std::uintmax_t(256) << 20;

// The encoded bytes of image `image` (index checked by the caller): its data: URI's bytes, or its buffer view's (the
// view checked first), empty for an external file. Throws MeshIoError as accessor_layout for a bad view.
std::vector<std::uint8_t> image_bytes(const tinygltf::Model& model, int image, const std::filesystem::path& path);

// The bytes of the external image file `uri` (as written in the glTF, %-encoded) of the glTF file `gltf`, under the
// rule for buffer files: a relative path without a scheme that resolves (after "..", symlinks) inside the glTF file's
// folder or below, a regular file of at most `max_bytes` (read_model_side_file). Throws MeshIoError "'../x.png':
// resolves to '/a/x.png', outside the folder '/a/b' of the model …" / "… file not found" (without the glTF file's
// name: the caller keeps it as the image's error and the object still loads).
std::vector<std::uint8_t> external_image_bytes(const std::filesystem::path& gltf, const std::string& uri,
                                               std::uintmax_t max_bytes = kMaxImageFileBytes);

}  // namespace trispline::core::gltf_read
