// trispline::core materials — glTF 2.0 metallic-roughness materials, their textures and images, and the parts
// (source nodes) of an object loaded from a file with several meshes or nodes.
//
// An object's TriMesh::face_material holds, per triangle, an index into its MaterialSet::materials, or
// kMaterialInside for cut surfaces (DFFD caps, incision walls: the object's inside colour). An object without a
// MaterialSet (or with an empty one) draws slot 0 in its object colour (Solid shading), as primitives do.
//
// Images keep the encoded bytes they were read from (`encoded`), so an export writes the source file unchanged;
// `rgba8` is the decoded picture (OpenImageIO) the viewport samples. A texture that could not be read keeps its
// `uri` and an `error`; the viewport shows Blender's magenta placeholder and an export writes the material
// without the image.
//
// Sources: Khronos glTF 2.0 specification §3.9 (materials), §3.8 (textures, images, samplers).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace trispline::core {

// A decoded or unreadable image of a material texture.
struct MaterialImage {
  std::string name;                   // glTF image name, or the file name; may be empty
  std::string uri;                    // the file it came from, relative to the model's folder ("" when embedded)
  std::string mime_type;              // "image/png", "image/jpeg", ... of `encoded` ("" when unreadable)
  std::vector<std::uint8_t> encoded;  // the source file's bytes, as read (empty when unreadable)
  int width = 0, height = 0;          // pixels of `rgba8` (0 when unreadable)
  std::vector<std::uint8_t> rgba8;    // width × height × 4, rows top to bottom, sRGB-encoded colour, straight alpha
  std::string error;                  // why it could not be read ("" when it was)
  bool readable() const { return error.empty() && width > 0 && height > 0; }
};

// glTF sampler values (the GL enums, glTF 2.0 §5.26).
enum class TextureWrap : int { Repeat = 10497, ClampToEdge = 33071, MirroredRepeat = 33648 };
enum class TextureFilter : int {
  Unset = 0,
  Nearest = 9728,
  Linear = 9729,
  NearestMipmapNearest = 9984,
  LinearMipmapNearest = 9985,
  NearestMipmapLinear = 9986,
  LinearMipmapLinear = 9987
};

struct TextureSampler {
  TextureWrap wrap_s = TextureWrap::Repeat;
  TextureWrap wrap_t = TextureWrap::Repeat;
  TextureFilter mag_filter = TextureFilter::Unset;  // Unset: the viewer's choice (linear)
  TextureFilter min_filter = TextureFilter::Unset;  // Unset: the viewer's choice (trilinear)
  bool operator==(const TextureSampler&) const = default;
};

// A material's use of an image. `image` < 0: no texture.
struct MaterialTexture {
  int image = -1;    // index into MaterialSet::images
  int texcoord = 0;  // TEXCOORD_n set; trispline meshes carry one set (TriMesh::uvs), so 0
  TextureSampler sampler;
  double scale = 1.0;  // normalTexture.scale, occlusionTexture.strength; 1 for the others
  bool present() const { return image >= 0; }
};

enum class AlphaMode { Opaque, Mask, Blend };

// One glTF 2.0 metallic-roughness material. Colours are linear RGB(A) factors in [0,1] (base colour textures are
// sRGB-encoded and multiplied after decoding, glTF 2.0 §3.9.2).
struct Material {
  std::string name;
  glm::dvec4 base_color{1.0};                  // baseColorFactor, linear RGBA
  MaterialTexture base_color_texture;          // sRGB RGBA
  double metallic = 1.0;                       // metallicFactor
  double roughness = 1.0;                      // roughnessFactor
  MaterialTexture metallic_roughness_texture;  // B = metallic, G = roughness
  MaterialTexture normal_texture;              // tangent-space normal map; scale = normalTexture.scale
  MaterialTexture occlusion_texture;           // R = occlusion; scale = strength
  glm::dvec3 emissive{0.0};                    // emissiveFactor, linear RGB
  MaterialTexture emissive_texture;            // sRGB RGB
  AlphaMode alpha_mode = AlphaMode::Opaque;
  double alpha_cutoff = 0.5;  // AlphaMode::Mask only
  bool double_sided = false;
};

// An object's materials and the images their textures use.
struct MaterialSet {
  std::vector<Material> materials;                           // indexed by TriMesh::face_material
  std::vector<std::shared_ptr<const MaterialImage>> images;  // indexed by MaterialTexture::image
  bool empty() const { return materials.empty(); }
  bool has_textures() const {
    for (const Material& m : materials)
      if (m.base_color_texture.present()) return true;
    return false;
  }
};

// A node of the file an object was loaded from: the object's rest mesh is every part's mesh, in node order, with
// its node's world transform applied. Parts let an export write the file's node tree back while the object is not
// deformed; instances (nodes sharing one mesh) share `mesh_index`.
struct MeshPart {
  std::string name;                                  // node name ("" → the object's name alone on export)
  int mesh_index = 0;                                // the file's mesh this node draws (instances share it)
  glm::dmat4 world{1.0};                             // node world transform in the file (object space of the rest mesh)
  std::uint32_t first_vertex = 0, vertex_count = 0;  // its vertices in the rest mesh
  std::uint32_t first_triangle = 0, triangle_count = 0;  // its triangles in the rest mesh
};

}  // namespace trispline::core
