#include "core/mesh/mesh_clip_gltf.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/mesh/mesh_io.h"

namespace trispline::core::clip_gltf {
namespace {

template <class T>
double as(const unsigned char* q) {
  T v;
  std::memcpy(&v, q, sizeof v);
  return static_cast<double>(v);
}

// One accessor component; normalised integers per glTF 2.0 §3.11 (signed: max(c / max, −1)).
double component(const unsigned char* q, int ctype, bool nrm) {
  using namespace std;
  switch (ctype) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return as<float>(q);
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return nrm ? max(as<int8_t>(q) / 127.0, -1.0) : as<int8_t>(q);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return nrm ? as<uint8_t>(q) / 255.0 : as<uint8_t>(q);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return nrm ? max(as<int16_t>(q) / 32767.0, -1.0) : as<int16_t>(q);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return nrm ? as<uint16_t>(q) / 65535.0 : as<uint16_t>(q);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return nrm ? as<uint32_t>(q) / 4294967295.0 : as<uint32_t>(q);
    default:
      return std::nan("");
  }
}

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

tinygltf::Model parse_gltf(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw MeshIoError(quoted_path(path) + ": file not found");
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const bool ok = lower_extension(path) == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, path.string())
                                                  : loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
  if (!ok) throw MeshIoError(quoted_path(path) + ": cannot parse glTF file: " + (err.empty() ? "unknown error" : err));
  return model;
}

// Accessor `index` as #count × comps doubles (glTF 2.0 §3.6.2; normalised integers per §3.11 table). Sparse
// substitution (§3.6.2.3) is applied when `sparse`; base POSITION/NORMAL skip it, as load_mesh does.
std::vector<double> read_accessor(const tinygltf::Model& model, int index, int comps, const std::string& what,
                                  const std::filesystem::path& path, bool sparse) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    throw MeshIoError(quoted_path(path) + ": " + what + " accessor index out of range");
  const auto& acc = model.accessors[index];
  if (tinygltf::GetNumComponentsInType(acc.type) != comps)
    throw MeshIoError(quoted_path(path) + ": " + what + " accessor has the wrong type");
  const int csize = tinygltf::GetComponentSizeInBytes(acc.componentType);
  if (csize <= 0) throw MeshIoError(quoted_path(path) + ": " + what + " has an unknown component type");
  auto view_bytes = [&](int view_index, std::size_t offset, std::size_t stride_default, std::size_t count,
                        std::size_t elem) -> std::pair<const unsigned char*, std::size_t> {
    if (view_index < 0 || view_index >= static_cast<int>(model.bufferViews.size()))
      throw MeshIoError(quoted_path(path) + ": " + what + " buffer view out of range");
    const auto& view = model.bufferViews[view_index];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
      throw MeshIoError(quoted_path(path) + ": " + what + " buffer out of range");
    const auto& buf = model.buffers[view.buffer].data;
    const std::size_t stride = view.byteStride ? view.byteStride : stride_default;
    const std::size_t start = view.byteOffset + offset;
    if (count > 0 && start + stride * (count - 1) + elem > buf.size())
      throw MeshIoError(quoted_path(path) + ": " + what + " accessor runs past the end of its buffer");
    return {buf.data() + start, stride};
  };
  const std::size_t elem = static_cast<std::size_t>(csize) * comps;
  std::vector<double> out(acc.count * comps, 0.0);
  if (acc.bufferView >= 0) {
    const auto [p, stride] = view_bytes(acc.bufferView, acc.byteOffset, elem, acc.count, elem);
    for (std::size_t i = 0; i < acc.count; ++i)
      for (int c = 0; c < comps; ++c)
        out[i * comps + c] = component(p + stride * i + c * csize, acc.componentType, acc.normalized);
  }
  if (sparse && acc.sparse.isSparse && acc.sparse.count > 0) {
    const auto n = static_cast<std::size_t>(acc.sparse.count);
    const int isize = tinygltf::GetComponentSizeInBytes(acc.sparse.indices.componentType);
    const auto [ip, istride] =
        view_bytes(acc.sparse.indices.bufferView, acc.sparse.indices.byteOffset, isize, n, isize);
    const auto [vp, vstride] = view_bytes(acc.sparse.values.bufferView, acc.sparse.values.byteOffset, elem, n, elem);
    for (std::size_t k = 0; k < n; ++k) {
      const double id = component(ip + istride * k, acc.sparse.indices.componentType, false);
      if (!(id >= 0 && id < static_cast<double>(acc.count)))
        throw MeshIoError(quoted_path(path) + ": " + what + " sparse index out of range");
      for (int c = 0; c < comps; ++c)
        out[static_cast<std::size_t>(id) * comps + c] =
            component(vp + vstride * k + c * csize, acc.componentType, acc.normalized);
    }
  }
  return out;  // finiteness is checked by the callers (keys: invalid_argument; geometry: MeshIoError)
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
                         bool rotation, const std::string& at, const std::filesystem::path& path) {
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
  smp.times = read_accessor(model, sampler.input, 1, "sampler input", path);
  smp.values = read_accessor(model, sampler.output, comps, "sampler output", path);
  if (smp.times.empty()) throw std::invalid_argument(at + ": empty sampler (no keys)");
  for (std::size_t k = 0; k < smp.times.size(); ++k)
    if (!std::isfinite(smp.times[k]) || (k > 0 && smp.times[k] < smp.times[k - 1]))
      throw std::invalid_argument(at + ": key times must be finite and increasing");
  for (double v : smp.values)
    if (!std::isfinite(v)) throw std::invalid_argument(at + ": non-finite key value");
  const std::size_t need = smp.times.size() * width * (smp.interp == Interp::Cubic ? 3 : 1);
  if (smp.values.size() != need)
    throw std::invalid_argument(at + ": sampler output has " + std::to_string(smp.values.size()) +
                                " values, expected " + std::to_string(need));
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
