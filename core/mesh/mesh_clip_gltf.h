// trispline::core::clip_gltf — glTF 2.0 animation data for MeshClip (internal to core/mesh; tinygltf types). Files are
// opened and accessors decoded through gltf_read.h.
//
//   AnimSampler     one sampler's keys; read_sampler validates them, sample_channel evaluates STEP, LINEAR (slerp for
//                   rotations) and CUBICSPLINE (Hermite with tangents scaled by the key interval) — §3.11, Appendix C
//   node_trs        node-local T · R · S (§3.5.3), the same operations as gltf_io.cpp, so rest transforms match
//                   load_mesh's bit for bit
#pragma once

#include <tiny_gltf.h>  // Debian's shared tinygltf: no configuration macros (see gltf_io.cpp)

#include <cstddef>
#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <vector>

#include "core/mesh/gltf_read.h"

namespace trispline::core::clip_gltf {

std::string quoted_path(const std::filesystem::path& p);  // 'p'

enum class Interp { Step, Linear, Cubic };

struct AnimSampler {
  Interp interp = Interp::Linear;
  int width = 0;               // values per key: 3 (translation, scale), 4 (rotation x y z w), #targets (weights)
  std::vector<double> times;   // #K ≥ 1, finite, non-decreasing, seconds
  std::vector<double> values;  // #K × width, or #K × 3 × width for CUBICSPLINE (in-tangent, value, out-tangent)
};

// Reads and checks a sampler for a channel of `width` values per key whose output accessor has `comps` components
// (weights: SCALAR, #targets per key; `rotation`: VEC4, LINEAR/STEP keys normalised to unit quaternions). Counts are
// checked before anything is decoded; the keys and values read are taken from `values_left` (the clip's share of
// gltf_read::kMaxClipValues). Throws std::invalid_argument "<at>: ..." (unknown interpolation, no keys, input not
// SCALAR, wrong output type or count, non-finite or decreasing times, non-finite values, zero quaternion);
// MeshIoError for bad accessors or when `values_left` is too small.
AnimSampler read_sampler(const tinygltf::Model& model, const tinygltf::AnimationSampler& sampler, int width, int comps,
                         bool rotation, const std::string& at, const std::filesystem::path& path,
                         std::size_t& values_left);

// Value at time t (clamped to the first/last key) into out[0 .. width). `rotation`: slerp (shortest arc) for
// LINEAR, and the result normalised.
void sample_channel(const AnimSampler& smp, double t, bool rotation, double* out);

glm::dmat4 node_trs(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s);

}  // namespace trispline::core::clip_gltf
