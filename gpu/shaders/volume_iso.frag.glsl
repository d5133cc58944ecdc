#version 430 core
// Ray casting of the iso-surface D = u_iso of a scalar trivariate B-spline (seed §7.3), exactly on the spline: the
// GLSL twin, in float, of core::iso_ray_hit (core/volume/iso_raycast.h), step by step:
//   1. the pixel's ray: origin on the near plane, direction towards NDC depth 0, both built in view space (where they
//      are small, so their difference keeps its precision) and mapped to index space;
//   2. clipped to the grid box [0, n−1]³ and to s ≥ 0 (s = index-space arc length from the near plane);
//   3. the signs of D − iso at s_m = m·u_step from the box entry and at the exit, front to back: the bricks of
//      u_bricks are walked (a 3D DDA) and the samples of a brick whose range excludes iso take its sign unevaluated;
//      in the other bricks a sample is evaluated fast (below) and, when |D − iso| is large, the next samples that the
//      brick's slope bound keeps on the same side take its sign too;
//   4. a sample whose fast sign differs from the previous sample's, or is uncertain, is evaluated exactly: the first
//      exact sign change brackets the crossing (zero counts as positive), refined by Illinois regula falsi (Hadwiger
//      et al. 2005) on exact values;
//   5. exact D is the tensor-product B-spline of order ORDER over the control points texelFetch'ed from u_controls
//      (clamped indices; uniform knots as core::VolumeSpline, weights of core::uniform_bspline_weights), its gradient
//      from the derivative weights; world normal −∇D / |∇D| through u_gradient_to_world.
// The fast value (step 3) is the same spline from 2³ trilinear fetches (one for ORDER 2): per axis two neighbouring
// weights are merged into one GL_LINEAR fetch placed at their ratio (Sigg & Hadwiger 2005, GPU Gems 2 ch. 20). Its
// error is below eps = 3 · u_filter_error · (max − min of the brick's controls) + roundoff, u_filter_error bounding the
// filter's weight error per axis, so a fast value with |f| > eps has the exact sign: the signs the march uses are the
// exact ones and it finds the bracket the plain exact march finds.
// llvmpipe runs both sides of every branch (masked SIMD lanes) and a loop body at least once, so the costly steps sit
// in loops that only run while a lane needs them: the brick walk innermost, then fast samples, then exact rounds.
// The refinement evaluates from the (ORDER + 1)³ control points around the bracket (two spans per axis: the bracket
// is at most one index unit long), fetched once.
// gl_FragDepth is the hit's depth, so meshes drawn with the depth test combine; misses are discarded.
// Defines: ORDER (2, 3, 4; default 4); OUTPUT_HITS: outputs world position (w = 1) to location 0 and the world
// normal to location 1 (RGBA32F attachments, for read-back) instead of the shaded colour.
#ifndef ORDER
#define ORDER 4
#endif
#define WIN (ORDER + 1)  // window of the refinement, control points per axis
#include "volume_spline.glsl"  // D (spline_value, fast_value), pixel_ray_in_grid, linear_to_srgb

layout(binding = 1) uniform sampler3D u_bricks;    // RGBA32F per brick: min, max, slope (core::VolumeRangeGrid), 0
uniform int u_brick;                 // index units per brick axis
uniform ivec3 u_brick_dims;          // bricks per axis
uniform float u_iso;                 // iso-level, the volume's units
uniform float u_step;                // march step, index units, ≤ 1
uniform float u_filter_error;        // bound of GL_LINEAR's weight error per axis (2^-8: 8-bit fractions)
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

// The refinement's window: control points g_window_first + (a, b, c), a, b, c < WIN (clamped indices).
float g_window[WIN * WIN * WIN];
ivec3 g_window_first;

// Loads the window covering the spans of index points pa and pb (at most one span apart per axis).
void load_window(vec3 pa, vec3 pb) {
  int f0, f1;
  float w[ORDER], dw[ORDER];
  for (int axis = 0; axis < 3; ++axis) {
    axis_basis(pa[axis], u_dims[axis], f0, w, dw);
    axis_basis(pb[axis], u_dims[axis], f1, w, dw);
    g_window_first[axis] = min(f0, f1);
  }
  for (int c = 0; c < WIN; ++c) {
    int iz = clamp(g_window_first.z + c, 0, u_dims.z - 1);
    for (int b = 0; b < WIN; ++b) {
      int iy = clamp(g_window_first.y + b, 0, u_dims.y - 1);
      for (int a = 0; a < WIN; ++a)
        g_window[a + WIN * (b + WIN * c)] =
            texelFetch(u_controls, ivec3(clamp(g_window_first.x + a, 0, u_dims.x - 1), iy, iz), 0).r;
    }
  }
}

// Weights (and derivatives) of the window's controls on one axis at t: the basis shifted by one when t's span is the
// window's second.
void window_axis(float t, int axis, out float w[WIN], out float dw[WIN]) {
  int first;
  float v[ORDER], dv[ORDER];
  axis_basis(t, u_dims[axis], first, v, dv);
  bool shifted = first > g_window_first[axis];
  for (int r = 0; r < WIN; ++r) {
    float a = r < ORDER ? v[min(r, ORDER - 1)] : 0.0, b = r > 0 ? v[max(r - 1, 0)] : 0.0;
    float da = r < ORDER ? dv[min(r, ORDER - 1)] : 0.0, db = r > 0 ? dv[max(r - 1, 0)] : 0.0;
    w[r] = shifted ? b : a;
    dw[r] = shifted ? db : da;
  }
}

// Exact D at p from the window.
float window_value(vec3 p) {
  float wx[WIN], wy[WIN], wz[WIN], d[WIN];
  window_axis(p.x, 0, wx, d);
  window_axis(p.y, 1, wy, d);
  window_axis(p.z, 2, wz, d);
  float sum = 0.0;
  for (int c = 0; c < WIN; ++c) {
    float sy = 0.0;
    for (int b = 0; b < WIN; ++b) {
      float sx = 0.0;
      for (int a = 0; a < WIN; ++a) sx += wx[a] * g_window[a + WIN * (b + WIN * c)];
      sy += wy[b] * sx;
    }
    sum += wz[c] * sy;
  }
  return sum;
}

// ∇D per index unit at p from the window.
vec3 window_gradient(vec3 p) {
  float wx[WIN], wy[WIN], wz[WIN], dx[WIN], dy[WIN], dz[WIN];
  window_axis(p.x, 0, wx, dx);
  window_axis(p.y, 1, wy, dy);
  window_axis(p.z, 2, wz, dz);
  vec3 g = vec3(0.0);
  for (int c = 0; c < WIN; ++c) {
    vec3 gy = vec3(0.0);  // (∂x, ∂y, value) contracted over x and y
    for (int b = 0; b < WIN; ++b) {
      float s0 = 0.0, s1 = 0.0;
      for (int a = 0; a < WIN; ++a) {
        float q = g_window[a + WIN * (b + WIN * c)];
        s0 += wx[a] * q, s1 += dx[a] * q;
      }
      gy += vec3(wy[b] * s1, dy[b] * s0, wy[b] * s0);
    }
    g += vec3(wz[c] * gy.x, wz[c] * gy.y, dz[c] * gy.z);
  }
  return g;
}

// Illinois regula falsi on [a, b] with f(a) = fa, f(b) = fb of opposite signs, f from the loaded window; returns the
// crossing's s.
float refine_crossing(vec3 entry, vec3 u, float a, float b, float fa, float fb) {
  int side = 0;
  for (int it = 0; it < kRefineIterations && b - a > kRefineTolerance; ++it) {
    float c = b - fb * (b - a) / (fb - fa);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    float fc = window_value(entry + c * u) - u_iso;
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

void main() {
  // 1.–2. The ray, clipped to the grid box.
  vec3 entry, u;
  float len;
  if (!pixel_ray_in_grid(entry, u, len)) discard;
  // 3.–4. March: samples m = 0…last at s = m·u_step, the last at len.
  int last = int(ceil(len / u_step));
  float u_l1 = abs(u.x) + abs(u.y) + abs(u.z);
  int m = 0;
  int brick_end = -1;         // last sample of the current brick whose range holds iso
  float eps = 0.0;            // that brick's bound of |fast − exact|
  float change = 0.0;         // that brick's bound of |D(s_{m+1}) − D(s_m)|
  bool have_prev = false;     // sample m − 1 has a sign
  bool neg_prev = false;      // its sign (D − iso < 0)
  bool found = false;
  float f_m = 0.0;            // exact D − iso at sample m
  while (m <= last) {
    // Fast march to a sample whose sign differs from the previous sample's or is uncertain.
    while (true) {
      bool differs = false;
      // Walk the bricks whose range excludes iso (their samples have its sign) to the next one holding it.
      while (m <= last && m > brick_end) {
        float s = m >= last ? len : float(m) * u_step;
        vec3 p = entry + s * u;
        ivec3 b = clamp(ivec3(floor(p / float(u_brick))), ivec3(0), u_brick_dims - 1);
        vec4 r = texelFetch(u_bricks, b, 0);
        vec3 lo = vec3(b * u_brick), hi = lo + float(u_brick);
        float exit_s = 3.0e38;
        for (int a = 0; a < 3; ++a) {
          if (u[a] > 0.0) exit_s = min(exit_s, (hi[a] - p[a]) / u[a]);
          if (u[a] < 0.0) exit_s = min(exit_s, (lo[a] - p[a]) / u[a]);
        }
        int e = int(min(floor((s + max(exit_s, 0.0)) / u_step), float(last)));
        e = max(e, m);
        if (r.x > u_iso || r.y < u_iso) {
          bool neg = r.y < u_iso;
          if (have_prev && neg != neg_prev) {
            differs = true;
            break;
          }
          have_prev = true, neg_prev = neg;
          m = e + 1;
        } else {
          brick_end = e;
          eps = 3.0 * u_filter_error * (r.y - r.x) + 2e-5 * max(abs(r.x), abs(r.y));
          change = r.z * u_l1 * u_step;
        }
      }
      if (differs || m > last) break;
      float f = fast_value(entry + (m >= last ? len : float(m) * u_step) * u) - u_iso;
      if (abs(f) <= eps) break;  // uncertain
      bool neg = f < 0.0;
      if (have_prev && neg != neg_prev) break;
      have_prev = true, neg_prev = neg;
      // The samples within (|f| − eps) / change steps keep the sign (the slope bound holds on the brick).
      float k = change > 0.0 ? floor(0.999 * (abs(f) - eps) / change) : 0.0;
      m = int(min(float(m) + 1.0 + k, float(brick_end + 1)));
    }
    if (m > last) break;
    f_m = spline_value(entry + (m >= last ? len : float(m) * u_step) * u) - u_iso;
    bool neg = f_m < 0.0;
    if (have_prev && neg != neg_prev) {
      found = true;
      break;
    }
    have_prev = true, neg_prev = neg;
    ++m;
  }
  if (!found) discard;
  // 4. Refine on [s_{m−1}, s_m].
  float sa = float(m - 1) * u_step, sb = m >= last ? len : float(m) * u_step;
  load_window(entry + sa * u, entry + sb * u);
  float s_hit = refine_crossing(entry, u, sa, sb, window_value(entry + sa * u) - u_iso, f_m);
  vec3 p = entry + s_hit * u;
  vec4 clip = u_index_to_clip * vec4(p, 1.0);
  float ndc_z = clip.z / clip.w;
  if (ndc_z > 1.0) discard;
  gl_FragDepth = 0.5 * (gl_DepthRange.diff * ndc_z + gl_DepthRange.near + gl_DepthRange.far);
  // 5. Normal and output.
  vec3 g = u_gradient_to_world * window_gradient(p);
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
