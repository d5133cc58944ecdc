#version 430 core
// Ray casting of the iso-surface D = u_iso of a scalar trivariate B-spline (seed §7.3), exactly on the spline: the
// GLSL twin, in float, of core::iso_ray_hit (core/volume/iso_raycast.h), step by step:
//   1. the pixel's ray: origin on the near plane, direction towards NDC depth 0, both built in view space (where they
//      are small, so their difference keeps its precision) and mapped to index space;
//   2. clipped to the grid box [0, n−1]³ and to s ≥ 0 (s = index-space arc length from the near plane);
//   3. D − iso sampled at s_m = m·u_step from the box entry and at the exit; bricks of u_bricks whose (min, max)
//      excludes iso are skipped to their last sample (the result does not change);
//   4. the first sign change (zero counts as positive) refined by Illinois regula falsi (Hadwiger et al. 2005);
//   5. D is the tensor-product B-spline of order ORDER over the control points texelFetch'ed from u_controls
//      (clamped indices; uniform knots as core::VolumeSpline, weights of core::uniform_bspline_weights), its gradient
//      from the derivative weights; world normal −∇D / |∇D| through u_gradient_to_world.
// gl_FragDepth is the hit's depth, so meshes drawn with the depth test combine; misses are discarded.
// Defines: ORDER (2, 3, 4; default 4); OUTPUT_HITS: outputs world position (w = 1) to location 0 and the world
// normal to location 1 (RGBA32F attachments, for read-back) instead of the shaded colour.
#ifndef ORDER
#define ORDER 4
#endif
layout(binding = 0) uniform sampler3D u_controls;  // R32F, nx × ny × nz control points, texel (i, j, l)
layout(binding = 1) uniform sampler3D u_bricks;    // RG32F, (min, max) of D per brick (core::VolumeRangeGrid)
uniform ivec3 u_dims;                // nx, ny, nz
uniform int u_brick;                 // index units per brick axis
uniform ivec3 u_brick_dims;          // bricks per axis
uniform float u_iso;                 // iso-level, the volume's units
uniform float u_step;                // march step, index units
uniform vec4 u_viewport;             // x, y, width, height (pixels) of the viewport the matrices map to
uniform mat4 u_inv_proj;             // inverse(projection)
uniform mat4 u_view_to_index;        // world_to_index · inverse(view)
uniform mat4 u_index_to_clip;        // projection · view · index_to_world
uniform mat4 u_index_to_world;       // millimetres
uniform mat3 u_gradient_to_world;    // (A⁻¹)ᵀ, A = linear part of index_to_world
#ifdef OUTPUT_HITS
layout(location = 0) out vec4 o_position;  // world xyz, w = 1
layout(location = 1) out vec4 o_normal;    // world unit normal −∇D / |∇D|, w = 0
#else
uniform vec3 u_albedo;               // linear RGB
uniform vec4 u_phong;                // ambient, diffuse, specular, shininess
layout(location = 0) out vec4 o_color;
#endif

const float kRefineTolerance = 1e-5;  // index units (float resolution of s over a few hundred voxels)
const int kRefineIterations = 24;

// Basis of one axis at index coordinate t: clamped control indices idx[r], weights w[r] and derivatives dw[r].
void axis_basis(float t, int n, out int idx[ORDER], out float w[ORDER], out float dw[ORDER]) {
  t = clamp(t, 0.0, float(n - 1));
#if ORDER % 2 == 0
  int span = clamp(int(floor(t)), 0, n - 2);
  float x = t - float(span);
#else
  int span = clamp(int(floor(t + 0.5)), 0, n - 1);
  float x = t - (float(span) - 0.5);
#endif
  int first = span - (ORDER - 1) / 2;
  for (int r = 0; r < ORDER; ++r) idx[r] = clamp(first + r, 0, n - 1);
#if ORDER == 2
  w[0] = 1.0 - x, w[1] = x;
  dw[0] = -1.0, dw[1] = 1.0;
#elif ORDER == 3
  w[0] = 0.5 * (1.0 - x) * (1.0 - x), w[1] = 0.5 + x - x * x, w[2] = 0.5 * x * x;
  dw[0] = x - 1.0, dw[1] = 1.0 - 2.0 * x, dw[2] = x;
#else
  float mx = 1.0 - x, x2 = x * x, x3 = x2 * x;
  w[0] = mx * mx * mx / 6.0;
  w[1] = (3.0 * x3 - 6.0 * x2 + 4.0) / 6.0;
  w[2] = (-3.0 * x3 + 3.0 * x2 + 3.0 * x + 1.0) / 6.0;
  w[3] = x3 / 6.0;
  dw[0] = -0.5 * mx * mx, dw[1] = 1.5 * x2 - 2.0 * x, dw[2] = -1.5 * x2 + x + 0.5, dw[3] = 0.5 * x2;
#endif
}

float spline_value(vec3 p) {
  int ix[ORDER], iy[ORDER], iz[ORDER];
  float wx[ORDER], wy[ORDER], wz[ORDER], d[ORDER];
  axis_basis(p.x, u_dims.x, ix, wx, d);
  axis_basis(p.y, u_dims.y, iy, wy, d);
  axis_basis(p.z, u_dims.z, iz, wz, d);
  float sum = 0.0;
  for (int c = 0; c < ORDER; ++c) {
    float sy = 0.0;
    for (int b = 0; b < ORDER; ++b) {
      float sx = 0.0;
      for (int a = 0; a < ORDER; ++a) sx += wx[a] * texelFetch(u_controls, ivec3(ix[a], iy[b], iz[c]), 0).r;
      sy += wy[b] * sx;
    }
    sum += wz[c] * sy;
  }
  return sum;
}

// ∇D per index unit.
vec3 spline_gradient(vec3 p) {
  int ix[ORDER], iy[ORDER], iz[ORDER];
  float wx[ORDER], wy[ORDER], wz[ORDER], dx[ORDER], dy[ORDER], dz[ORDER];
  axis_basis(p.x, u_dims.x, ix, wx, dx);
  axis_basis(p.y, u_dims.y, iy, wy, dy);
  axis_basis(p.z, u_dims.z, iz, wz, dz);
  vec3 g = vec3(0.0);
  for (int c = 0; c < ORDER; ++c) {
    vec3 gy = vec3(0.0);  // (∂x, ∂y, value) contracted over x and y
    for (int b = 0; b < ORDER; ++b) {
      float s0 = 0.0, s1 = 0.0;
      for (int a = 0; a < ORDER; ++a) {
        float q = texelFetch(u_controls, ivec3(ix[a], iy[b], iz[c]), 0).r;
        s0 += wx[a] * q, s1 += dx[a] * q;
      }
      gy += vec3(wy[b] * s1, dy[b] * s0, wy[b] * s0);
    }
    g += vec3(wz[c] * gy.x, wz[c] * gy.y, dz[c] * gy.z);
  }
  return g;
}

// Illinois regula falsi on [a, b] with f(a) = fa, f(b) = fb of opposite signs; returns the crossing's s.
float refine_crossing(vec3 entry, vec3 u, float a, float b, float fa, float fb) {
  int side = 0;
  for (int it = 0; it < kRefineIterations && b - a > kRefineTolerance; ++it) {
    float c = b - fb * (b - a) / (fb - fa);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    float fc = spline_value(entry + c * u) - u_iso;
    if (fc == 0.0) return c;
    if ((fc < 0.0) == (fa < 0.0)) {
      a = c, fa = fc;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = c, fb = fc;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (a + b);
}

#ifndef OUTPUT_HITS
vec3 linear_to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
#endif

void main() {
  // 1. The ray.
  vec2 ndc = 2.0 * (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw - 1.0;
  vec4 pn = u_inv_proj * vec4(ndc, -1.0, 1.0);
  vec4 pm = u_inv_proj * vec4(ndc, 0.0, 1.0);
  pn /= pn.w;
  pm /= pm.w;
  vec3 o = (u_view_to_index * vec4(pn.xyz, 1.0)).xyz;
  vec3 u = normalize(mat3(u_view_to_index) * (pm.xyz - pn.xyz));
  // 2. Clip to the grid box.
  vec3 box = vec3(u_dims - 1);
  float s_lo = 0.0, s_hi = 3.0e38;
  for (int a = 0; a < 3; ++a) {
    if (u[a] == 0.0) {
      if (o[a] < 0.0 || o[a] > box[a]) discard;
      continue;
    }
    float s0 = -o[a] / u[a], s1 = (box[a] - o[a]) / u[a];
    s_lo = max(s_lo, min(s0, s1));
    s_hi = min(s_hi, max(s0, s1));
  }
  if (!(s_lo <= s_hi)) discard;
  vec3 entry = o + s_lo * u;
  float len = s_hi - s_lo;
  // 3. March.
  int last = int(ceil(len / u_step));
  int m = 0;
  float s_prev = 0.0, f_prev = spline_value(entry) - u_iso;
  bool skip_checked = false;
  bool found = false;
  float s_hit = 0.0;
  while (m < last) {
    if (!skip_checked) {
      vec3 p = entry + s_prev * u;
      ivec3 b = clamp(ivec3(floor(p / float(u_brick))), ivec3(0), u_brick_dims - 1);
      vec2 r = texelFetch(u_bricks, b, 0).rg;
      skip_checked = true;
      if (r.x > u_iso || r.y < u_iso) {
        vec3 lo = vec3(b * u_brick), hi = lo + float(u_brick);
        float exit_s = 3.0e38;
        for (int a = 0; a < 3; ++a) {
          if (u[a] > 0.0) exit_s = min(exit_s, (hi[a] - p[a]) / u[a]);
          if (u[a] < 0.0) exit_s = min(exit_s, (lo[a] - p[a]) / u[a]);
        }
        float j = min(floor((s_prev + max(exit_s, 0.0)) / u_step), float(last));
        if (j > float(m)) {
          m = int(j);
          s_prev = m >= last ? len : float(m) * u_step;
          f_prev = spline_value(entry + s_prev * u) - u_iso;
          continue;
        }
      }
    }
    ++m;
    float s = m >= last ? len : float(m) * u_step;
    float fs = spline_value(entry + s * u) - u_iso;
    if ((fs < 0.0) != (f_prev < 0.0)) {
      // 4. Refine.
      s_hit = refine_crossing(entry, u, s_prev, s, f_prev, fs);
      found = true;
      break;
    }
    s_prev = s, f_prev = fs;
    skip_checked = false;
  }
  if (!found) discard;
  vec3 p = entry + s_hit * u;
  vec4 clip = u_index_to_clip * vec4(p, 1.0);
  float ndc_z = clip.z / clip.w;
  if (ndc_z > 1.0) discard;
  gl_FragDepth = 0.5 * (gl_DepthRange.diff * ndc_z + gl_DepthRange.near + gl_DepthRange.far);
  // 5. Normal and output.
  vec3 g = u_gradient_to_world * spline_gradient(p);
  vec3 n = dot(g, g) > 0.0 ? -normalize(g) : vec3(0.0);
#ifdef OUTPUT_HITS
  o_position = vec4((u_index_to_world * vec4(p, 1.0)).xyz, 1.0);
  o_normal = vec4(n, 0.0);
#else
  // Blinn–Phong with a headlight: the light comes from the eye, so the half vector is the view vector.
  vec3 v = -normalize(mat3(u_index_to_world) * u);
  if (dot(n, v) < 0.0) n = -n;  // two-sided: the inside of a clipped or entered object is lit too
  float lambert = max(dot(n, v), 0.0);
  vec3 c = u_albedo * (u_phong.x + u_phong.y * lambert) + vec3(u_phong.z * pow(lambert, u_phong.w));
  o_color = vec4(linear_to_srgb(c), 1.0);
#endif
}
