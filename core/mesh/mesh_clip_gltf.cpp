#include "core/mesh/mesh_clip_gltf.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/mesh/mesh_io.h"

namespace trispline::core::clip_gltf {

using gltf_read::kMaxClipValues;

namespace {

// Spherical linear interpolation of unit quaternions (glTF 2.0 Appendix C, shortest arc), normalised.
glm::dquat slerp(glm::dquat a, glm::dquat b, double u) {
  double d = glm::dot(a, b);
  if (d < 0) {
    b = -b;
    d = -d;
  }
  if (d > 1.0 - 1e-12) return glm::normalize(a * (1.0 - u) + b * u);
  const double angle = std::acos(d), s = std::sin(angle);
  return glm::normalize(a * (std::sin((1.0 - u) * angle) / s) + b * (std::sin(u * angle) / s));
}

}  // namespace

std::string quoted_path(const std::filesystem::path& p) {
  std::string q(1, '\'');  // appended piecewise: GCC 12 warns (-Wrestrict, false positive) on "'" + s
  q += p.string();
  q += '\'';
  return q;
}

// Node-local matrix T · R · S (glTF 2.0 §3.5.3), the same operations as gltf_io.cpp's, so the rest pose is
// bit-identical to load_mesh's transforms.
glm::dmat4 node_trs(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s) {
  glm::dmat4 m(1.0);
  m[3] = glm::dvec4(t, 1.0);
  m = m * glm::dmat4(glm::mat3_cast(r));
  glm::dmat4 sm(1.0);
  for (int i = 0; i < 3; ++i) sm[i][i] = s[i];
  return m * sm;
}

// Evaluates `smp` at time t (clamped to its keys) into out[0 .. width). Rotations (quat) are slerped / normalised.
void sample_channel(const AnimSampler& smp, double t, bool quat, double* out) {
  const int w = smp.width;
  const auto& T = smp.times;
  const std::size_t nk = T.size();
  const bool cubic = smp.interp == Interp::Cubic;
  auto val = [&](std::size_t k, int c) { return cubic ? smp.values[(3 * k + 1) * w + c] : smp.values[k * w + c]; };
  std::size_t k = 0;
  double u = 0;
  if (t >= T.back()) {
    k = nk - 1;
  } else if (t > T.front()) {
    k = static_cast<std::size_t>(std::upper_bound(T.begin(), T.end(), t) - T.begin()) - 1;  // T[k] ≤ t < T[k+1]
    u = (t - T[k]) / (T[k + 1] - T[k]);
  }
  if (k + 1 >= nk || u == 0 || smp.interp == Interp::Step) {
    for (int c = 0; c < w; ++c) out[c] = val(k, c);
  } else if (smp.interp == Interp::Linear) {
    if (quat) {
      const glm::dquat q = slerp({val(k, 3), val(k, 0), val(k, 1), val(k, 2)},
                                 {val(k + 1, 3), val(k + 1, 0), val(k + 1, 1), val(k + 1, 2)}, u);
      out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = q.w;
      return;
    }
    for (int c = 0; c < w; ++c) out[c] = val(k, c) + u * (val(k + 1, c) - val(k, c));
  } else {  // Hermite spline, glTF 2.0 Appendix C: tangents scaled by the key interval
    const double td = T[k + 1] - T[k], u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    for (int c = 0; c < w; ++c) {
      const double b_k = smp.values[(3 * k + 2) * w + c], a_k1 = smp.values[(3 * (k + 1)) * w + c];
      out[c] = h00 * val(k, c) + h10 * td * b_k + h01 * val(k + 1, c) + h11 * td * a_k1;
    }
  }
  if (quat) {
    const glm::dquat q = glm::normalize(glm::dquat(out[3], out[0], out[1], out[2]));
    out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = q.w;
  }
}

AnimSampler read_sampler(const tinygltf::Model& model, const tinygltf::AnimationSampler& sampler, int width, int comps,
                         bool rotation, const std::string& at, const std::filesystem::path& path,
                         std::size_t& values_left) {
  AnimSampler smp;
  smp.width = width;
  if (sampler.interpolation == "STEP")
    smp.interp = Interp::Step;
  else if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty())
    smp.interp = Interp::Linear;
  else if (sampler.interpolation == "CUBICSPLINE")
    smp.interp = Interp::Cubic;
  else
    throw std::invalid_argument(at + ": unknown interpolation '" + sampler.interpolation + "'");
  // Counts first (read_model checked the accessors against their bytes), then the budget, then the values.
  const auto in = gltf_read::accessor_layout(model, sampler.input, "sampler input", path);
  const auto out = gltf_read::accessor_layout(model, sampler.output, "sampler output", path);
  if (in.comps != 1) throw std::invalid_argument(at + ": sampler input must be SCALAR key times");
  if (out.comps != comps)
    throw std::invalid_argument(at + ": sampler output has " + std::to_string(out.comps) +
                                " components per element, expected " + std::to_string(comps));
  if (in.count == 0) throw std::invalid_argument(at + ": empty sampler (no keys)");
  auto over_budget = [&] {
    return MeshIoError(quoted_path(path) + ": the clip's keys and other animation data need more than " +
                       std::to_string(kMaxClipValues) + " numbers (the limit for a clip)");
  };
  if (in.count > kMaxClipValues || out.count > kMaxClipValues) throw over_budget();  // products below cannot overflow
  const std::size_t per_key = static_cast<std::size_t>(width) * (smp.interp == Interp::Cubic ? 3 : 1);
  const std::size_t have = out.count * static_cast<std::size_t>(comps);
  if (have != in.count * per_key)
    throw std::invalid_argument(at + ": sampler output has " + std::to_string(have) + " values, expected " +
                                std::to_string(in.count * per_key));
  if (in.count + have > values_left) throw over_budget();
  values_left -= in.count + have;
  smp.times = gltf_read::read_accessor(model, sampler.input, 1, "sampler input", path, in.count);
  smp.values = gltf_read::read_accessor(model, sampler.output, comps, "sampler output", path, out.count);
  for (std::size_t k = 0; k < smp.times.size(); ++k)
    if (!std::isfinite(smp.times[k]) || (k > 0 && smp.times[k] < smp.times[k - 1]))
      throw std::invalid_argument(at + ": key times must be finite and increasing");
  for (double v : smp.values)
    if (!std::isfinite(v)) throw std::invalid_argument(at + ": non-finite key value");
  if (rotation && smp.interp != Interp::Cubic)  // keys as unit quaternions, so slerp is exact
    for (std::size_t k = 0; k < smp.times.size(); ++k) {
      double* q = smp.values.data() + 4 * k;
      const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      if (!(len > 0)) throw std::invalid_argument(at + ": zero rotation quaternion");
      for (int c = 0; c < 4; ++c) q[c] /= len;
    }
  return smp;
}

}  // namespace trispline::core::clip_gltf
