// Internal to trispline_mesh: assimp's materials (OBJ/MTL, Collada, FBX) → glTF 2.0 metallic-roughness Materials.
//
//   convert_assimp_materials  the scene's materials used by the loaded faces → MaterialSet, images decoded
//
// Mapping (assimp key ← MTL statement; Blender's OBJ importer makes the same choices where it makes one):
//   base_color        $clr.base (FBX/PBR) else $clr.diffuse (Kd), taken as linear RGB; alpha = $mat.opacity (d,
//                     1 − Tr); alpha < 1 → AlphaMode::Blend
//   base colour tex   BASE_COLOR else DIFFUSE (map_Kd)
//   alpha texture     OPACITY (map_d): the same image as map_Kd → its alpha channel; another image → its first
//                     channel (grey) written into the alpha of a combined RGBA image (nearest texel when sizes
//                     differ); AlphaMode::Mask, cutoff 0.5 (cut-outs such as leaves: sharp edges, no sorting)
//   normal texture    NORMALS (norm, FBX normal map) else HEIGHT (bump, map_Bump: OBJ exporters write normal maps
//                     there), scale = $tex.bumpmult (-bm), default 1
//   emissive          $clr.emissive (Ke); EMISSIVE / EMISSION_COLOR (map_Ke) → emissive texture, factor 1 when Ke
//                     is black or absent
//   metallic          $mat.metallicFactor (Pm) else 0 (Phong and Lambert materials are dielectric)
//   roughness         $mat.roughnessFactor (Pr) else from the Phong exponent Ns: 1 − √(clamp(Ns, 0, 1000) / 1000)
//                     (Blender's OBJ importer), 1 when the specular colour (Ks) is black or Ns absent
//   occlusion tex     AMBIENT_OCCLUSION (map_Ka is an ambient colour map, not occlusion: left out)
//   double_sided      $mat.twosided
//   sampler           aiTextureMapMode Wrap / Clamp / Mirror → Repeat / ClampToEdge / MirroredRepeat
// A texture path is read with read_model_side_file (the model's folder or below); FBX embedded textures ("*N" or a
// name assimp knows) from the scene. A file that cannot be read or decoded keeps its uri and the reason
// (MaterialImage::error); the material still refers to it (the viewport shows the placeholder).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/material.h"

struct aiScene;

namespace trispline::core {

// `used` lists the scene's material indices in the order they become slots 0, 1, …; a file whose only material is
// one assimp made up ("DefaultMaterial", or unnamed as OFF's and PLY's grey; no texture) gives null (the object keeps
// its colour). `model` is the file's
// path (textures are relative to its folder). Images over the texture budget are refused by their header.
std::shared_ptr<const MaterialSet> convert_assimp_materials(const aiScene& scene, const std::vector<unsigned>& used,
                                                            const std::filesystem::path& model);

}  // namespace trispline::core
