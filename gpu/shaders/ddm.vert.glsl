#version 430 core
// DDM tile instances (seed §5.3.2, hardware deformation displacement maps): every vertex of every instance of one
// tile mesh is placed here, T(u,v,w) = P(u,v) + N(u,v)·w·height (seed Eq. 5.1–5.2), its normal mapped exactly
// through the cofactor of T's Jacobian (seed §5.3.2 last paragraph, with the sampled derivatives of S instead of
// the ε trick). Step by step what core::ddm_evaluate does over core::DdmMapsBase, in float; gpu::DdmGl draws with
// it (paired with mesh.frag.glsl) and captures v_world / v_normal by transform feedback for tests.
//
// Attributes: 0 / 1 the tile's position (x, y, w) and unit normal (tile space); 2 / 3 its metamorphosis partner's
// (seed Eq. 5.3; the tile itself and u_alpha = 0 without one); per instance (divisor 1): 4 the chart's slot in the
// maps, 5 the cell origin, 6 the cell size (chart parameter units).
// Maps: SSBO binding 6, std430 float[]: slot, row j (v), column i (u), 18 floats per sample: P, N, S_u, S_v, N_u,
// N_v (core::DdmMaps). Bilinear interpolation with float weights from texelFetch-like reads — never the texture
// unit's GL_LINEAR, whose fixed-point weights (8 bits on NVIDIA) would break CPU/GPU parity (docs/decisions.md).
// Variant MATERIAL: the tile's uvs (attribute 13) passed on for mesh.frag.glsl's Material shading.
// Variant OUTLINE: pushed out along the screen-space normal by u_outline_px (the selection outline, as mesh.vert).
// Variant FOLLOW: the tiles follow their object's deformation (core::DdmLayerDeformation, core/scene/ddm_follow.h):
// per instance a host map of object space (attributes 7–9 the columns of its linear part, 10 its shift; normals by its
// cofactor), then u_model, then — with FFD — the object's lattice (ffd_eval.glsl, SSBOs 4/5) at
// p = A·x + b + u_param_offset clamped per instance to [11, 12] (a DFFD's sides), or E⁻¹(p) outside [0,1]³ when
// u_identity_outside (the global DFFD).
layout(location = 0) in vec3 a_tile_position;
layout(location = 1) in vec3 a_tile_normal;
layout(location = 2) in vec3 a_morph_position;
layout(location = 3) in vec3 a_morph_normal;
layout(location = 4) in int a_slot;
layout(location = 5) in vec2 a_origin;
layout(location = 6) in vec2 a_size;

layout(std430, binding = 6) readonly buffer DdmMapSamples { float ddm_samples[]; };
#ifdef MATERIAL
layout(location = 13) in vec2 a_tile_uv;  // the tile's own texture coordinates (texture-mapped tiles, seed Fig. 5.12)
out vec2 v_uv;
#endif
#ifdef FOLLOW
layout(location = 7) in vec3 a_host_c0;
layout(location = 8) in vec3 a_host_c1;
layout(location = 9) in vec3 a_host_c2;
layout(location = 10) in vec3 a_host_shift;
layout(location = 11) in vec3 a_param_lo;
layout(location = 12) in vec3 a_param_hi;
#ifdef FFD
#define FFD_NORMALS
#include "ffd_eval.glsl"
uniform mat3 u_embed_linear;        // A (world → parameters)
uniform vec3 u_embed_shift;         // b
uniform mat3 u_embed_inverse;       // A⁻¹
uniform vec3 u_param_offset;        // parameter units (seed §4.5 animation)
uniform int u_identity_outside;     // 1: outside [0,1]³ map by E⁻¹ (global DFFD)
#endif
#endif

uniform ivec2 u_resolution;   // samples per chart along u, v (≥ 2)
uniform ivec2 u_periodic;     // 1: the axis wraps modulo 1 (fract), 0: clamped to [0,1]
uniform float u_height;       // object units per tile unit of w
uniform mat2 u_tile_linear;   // DdmTileTransform::linear() = R · diag(scale)
uniform vec2 u_tile_shift;    // cell units
uniform vec2 u_offset;        // texture-space offset, chart parameter units (reduced modulo 1 on periodic axes)
uniform float u_alpha;        // metamorphosis weight (any real; 0 without a partner)
uniform mat4 u_model;         // object → world (identity when capturing object space)
uniform mat3 u_normal_matrix; // inverse transpose of u_model's 3×3
uniform mat4 u_view_proj;
out vec3 v_world;
out vec3 v_normal;
#ifdef OUTLINE
#include "outline.glsl"
#endif

// Parameter t on an axis of r samples → sample index i ∈ [0, r − 2] and weight f ∈ [0, 1] (core locate()).
void ddm_locate(float t, int r, bool periodic, out int i, out float f) {
  t = periodic ? t - floor(t) : clamp(t, 0.0, 1.0);
  float x = t * float(r - 1);
  i = min(int(x), r - 2);
  f = x - float(i);
}

vec3 ddm_get(uint base, uint k) {
  uint o = base + 3u * k;
  return vec3(ddm_samples[o], ddm_samples[o + 1u], ddm_samples[o + 2u]);
}

void main() {
  // Metamorphosis (Eq. 5.3): V = V1·(1 − α) + V2·α, normals renormalised.
  vec3 t = a_tile_position * (1.0 - u_alpha) + a_morph_position * u_alpha;
  vec3 tn = a_tile_normal * (1.0 - u_alpha) + a_morph_normal * u_alpha;
  float tl = length(tn);
  tn = tl > 0.0 ? tn / tl : (u_alpha < 0.5 ? a_tile_normal : a_morph_normal);
  // Tile space → cell → chart parameters.
  vec2 xy = u_tile_linear * (t.xy - 0.5) + 0.5 + u_tile_shift;
  vec2 uv = a_origin + a_size * xy + u_offset;
  int i, j;
  float fu, fv;
  ddm_locate(uv.x, u_resolution.x, u_periodic.x != 0, i, fu);
  ddm_locate(uv.y, u_resolution.y, u_periodic.y != 0, j, fv);
  const uint F = 18u;
  uint s00 = ((uint(a_slot) * uint(u_resolution.y) + uint(j)) * uint(u_resolution.x) + uint(i)) * F;
  uint s10 = s00 + F;
  uint s01 = s00 + uint(u_resolution.x) * F;
  uint s11 = s01 + F;
  vec3 q[6];
  for (uint k = 0u; k < 6u; ++k)
    q[k] = (ddm_get(s00, k) * (1.0 - fu) + ddm_get(s10, k) * fu) * (1.0 - fv) +
           (ddm_get(s01, k) * (1.0 - fu) + ddm_get(s11, k) * fu) * fv;
  float nl = length(q[1]);
  vec3 n = nl > 0.0 ? q[1] / nl : vec3(0.0, 0.0, 1.0);
  // T = S + n·w·h and its Jacobian J = [S'_u, S'_v]·diag(size)·L | h·n], S'_· = S_· + w·h·n_·.
  float wh = t.z * u_height;
  vec3 position = q[0] + wh * n;
  vec3 Tu = q[2] + wh * q[4];
  vec3 Tv = q[3] + wh * q[5];
  vec2 cx = a_size.x * vec2(u_tile_linear[0][0], u_tile_linear[1][0]);
  vec2 cy = a_size.y * vec2(u_tile_linear[0][1], u_tile_linear[1][1]);
  vec3 J0 = Tu * cx.x + Tv * cy.x;
  vec3 J1 = Tu * cx.y + Tv * cy.y;
  vec3 J2 = u_height * n;
  // cof(J)·n = det(J)·J⁻ᵀ·n: turned back where J reverses orientation (a mirrored chart, det J < 0).
  vec3 m = cross(J1, J2) * tn.x + cross(J2, J0) * tn.y + cross(J0, J1) * tn.z;
  if (dot(cross(J0, J1), J2) < 0.0) m = -m;
  float ml = length(m);
  vec3 normal = ml > 0.0 ? m / ml : n;
#ifdef FOLLOW
  mat3 H = mat3(a_host_c0, a_host_c1, a_host_c2);
  position = H * position + a_host_shift;
  vec3 hn = cross(H[1], H[2]) * normal.x + cross(H[2], H[0]) * normal.y + cross(H[0], H[1]) * normal.z;
  float hl = length(hn);
  normal = hl > 0.0 ? hn / hl : normal;
#endif
  vec3 world = (u_model * vec4(position, 1.0)).xyz;
  vec3 wn = u_normal_matrix * normal;
  float wl = length(wn);
  vec3 world_normal = wl > 0.0 ? wn / wl : normal;
#if defined(FOLLOW) && defined(FFD)
  vec3 p = clamp(u_embed_linear * world + u_embed_shift + u_param_offset, a_param_lo, a_param_hi);
  if (u_identity_outside != 0 && (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0))))) {
    world = u_embed_inverse * (p - u_embed_shift);
  } else {
    vec3 fp, fn;
    ffd_eval(p, world_normal, fp, fn);
    world = fp;
    world_normal = fn;
  }
#endif
  vec4 clip = u_view_proj * vec4(world, 1.0);
#ifdef OUTLINE
  clip = outline_push(clip, u_view_proj, world_normal);
#endif
  v_world = world;
  v_normal = world_normal;
#ifdef MATERIAL
  v_uv = a_tile_uv;
#endif
  gl_Position = clip;
}
