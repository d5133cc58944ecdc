#version 430 core
// Direct volume rendering of a scalar trivariate B-spline (seed §7.4, Fig. 7.7): emission–absorption along each
// pixel's ray through a 1-D transfer function — the GLSL twin, in float, of core::dvr_ray
// (core/volume/volume_dvr.h), step by step:
//   1. the pixel's ray as volume_iso.frag.glsl builds it (origin on the near plane, towards NDC depth 0), in index
//      space, clipped to the grid box [0, n−1]³;
//   2. the clipped length L cut into N = ⌈L / u_step⌉ segments (the last one shorter), each sampled at its middle;
//      a segment inside a brick whose value range (u_bricks: min, max of its controls) maps to zero opacity is
//      skipped with the rest of that brick;
//   3. a sample's colour c and opacity a per index unit from the transfer function (linear between its points,
//      constant beyond), absorbed as α = 1 − (1 − a)^ℓ over the segment length ℓ and composited front to back until
//      the opacity reaches u_opaque;
//   4. written premultiplied with the colour sRGB-encoded (rgb = srgb(C / A) · A, a = A), for blending with
//      (ONE, ONE_MINUS_SRC_ALPHA); gl_FragDepth is the depth of the first sample that added anything.
// D is the exact spline (volume_spline.glsl spline_value) with EXACT defined, else the fast value of 2³ GL_LINEAR
// fetches (within 3 · 2⁻⁸ · the brick's control range of it on GPUs; llvmpipe filters in float).
// Defines: ORDER (2, 3, 4; default 4), EXACT.
#ifndef ORDER
#define ORDER 4
#endif
#include "volume_spline.glsl"  // D (spline_value, fast_value), pixel_ray_in_grid, linear_to_srgb

#define MAX_POINTS 16  // core::kMaxTransferPoints

layout(binding = 1) uniform sampler3D u_bricks;  // RGBA32F per brick: min, max, slope (core::VolumeRangeGrid), 0
uniform int u_brick;                             // index units per brick axis
uniform ivec3 u_brick_dims;                      // bricks per axis
uniform float u_step;                            // segment length, index units
uniform float u_opaque;                          // the march ends at this opacity (core::kDvrOpaque)
uniform int u_tf_count;                          // transfer function points, 2…MAX_POINTS
uniform float u_tf_value[MAX_POINTS];            // increasing values, the volume's units
uniform vec4 u_tf_rgba[MAX_POINTS];              // linear rgb, opacity per index unit
uniform mat4 u_index_to_clip;                    // projection · view · index_to_world
layout(location = 0) out vec4 o_color;

vec4 transfer(float v) {
  if (!(v > u_tf_value[0])) return u_tf_rgba[0];
  for (int i = 1; i < u_tf_count; ++i)
    if (v < u_tf_value[i])
      return mix(u_tf_rgba[i - 1], u_tf_rgba[i], (v - u_tf_value[i - 1]) / (u_tf_value[i] - u_tf_value[i - 1]));
  return u_tf_rgba[u_tf_count - 1];
}

// The largest opacity over values [lo, hi]: 0 means nothing there is visible.
float max_opacity(float lo, float hi) {
  float m = max(transfer(lo).a, transfer(hi).a);
  for (int i = 0; i < u_tf_count; ++i)
    if (u_tf_value[i] > lo && u_tf_value[i] < hi) m = max(m, u_tf_rgba[i].a);
  return m;
}

void main() {
  // 1. The ray, clipped to the grid box.
  vec3 entry, u;
  float len;
  if (!pixel_ray_in_grid(entry, u, len)) discard;
  // 2.–3. March the segments.
  int segments = max(1, int(ceil(len / u_step)));
  vec3 color = vec3(0.0);
  float alpha = 0.0;
  float first_s = -1.0;  // the first sample that added anything
  int m = 0;
  while (m < segments && alpha < u_opaque) {
    float s0 = float(m) * u_step;
    float seg = min(u_step, len - s0);
    vec3 p = entry + (s0 + 0.5 * seg) * u;
    ivec3 b = clamp(ivec3(floor(p / float(u_brick))), ivec3(0), u_brick_dims - 1);
    vec4 r = texelFetch(u_bricks, b, 0);
    if (max_opacity(r.x, r.y) == 0.0) {
      vec3 lo = vec3(b * u_brick), hi = lo + float(u_brick);
      float exit_s = 3.0e38;
      for (int a = 0; a < 3; ++a) {
        if (u[a] > 0.0) exit_s = min(exit_s, (hi[a] - p[a]) / u[a]);
        if (u[a] < 0.0) exit_s = min(exit_s, (lo[a] - p[a]) / u[a]);
      }
      float s_exit = s0 + 0.5 * seg + max(exit_s, 0.0);
      m = max(m + 1, int(floor((s_exit - 0.5 * u_step) / u_step)) + 1);
      continue;
    }
#ifdef EXACT
    vec4 c = transfer(spline_value(p));
#else
    vec4 c = transfer(fast_value(p));
#endif
    if (c.a > 0.0) {
      float a = 1.0 - pow(1.0 - c.a, seg);
      color += (1.0 - alpha) * a * c.rgb;
      alpha += (1.0 - alpha) * a;
      if (first_s < 0.0) first_s = s0 + 0.5 * seg;
    }
    ++m;
  }
  if (!(alpha > 0.0)) discard;
  // 4. Premultiplied, sRGB-encoded; the depth of the front of what was seen.
  vec4 clip = u_index_to_clip * vec4(entry + first_s * u, 1.0);
  float ndc_z = clamp(clip.z / clip.w, -1.0, 1.0);
  gl_FragDepth = 0.5 * (gl_DepthRange.diff * ndc_z + gl_DepthRange.near + gl_DepthRange.far);
  o_color = vec4(linear_to_srgb(color / alpha) * alpha, alpha);
}
