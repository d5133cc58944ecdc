#version 430 core
// The scalar trivariate B-spline D of a volume (core::VolumeSpline) in GLSL, shared by the iso-surface ray caster
// (volume_iso.frag.glsl) and the direct volume renderer (volume_dvr.frag.glsl): uniform knots on the index grid, order
// ORDER (2, 3, 4; defined by the including shader), control points in u_controls (clamped indices).
//   axis_basis    one axis's first control index, weights and derivative weights at index coordinate t
//   spline_value  exact D: ORDER³ texelFetch
//   fast_value    D from 2³ GL_LINEAR fetches (one for ORDER 2; Sigg & Hadwiger 2005, GPU Gems 2 ch. 20), within
//                 3 · (filter weight error) · (the controls' range) of the exact value
//   pixel_ray_in_grid  the fragment's ray in index space, clipped to the grid box (as core::pixel_ray + the clip of
//                 core::iso_ray_hit / core::dvr_ray)
//   linear_to_srgb     the colour encoding of both shaders' output
layout(binding = 0) uniform sampler3D u_controls;  // R32F, nx × ny × nz control points, texel (i, j, l); GL_LINEAR
uniform ivec3 u_dims;                              // nx, ny, nz
uniform vec4 u_viewport;       // x, y, width, height (pixels) of the viewport the matrices map to (pixel_ray_in_grid)
uniform mat4 u_inv_proj;       // inverse(projection)
uniform mat4 u_view_to_index;  // world_to_index · inverse(view)

// Basis of one axis at index coordinate t: first (unclamped) control index, weights w[r] of control first + r and
// their derivatives dw[r].
void axis_basis(float t, int n, out int first, out float w[ORDER], out float dw[ORDER]) {
  t = clamp(t, 0.0, float(n - 1));
#if ORDER % 2 == 0
  int span = clamp(int(floor(t)), 0, n - 2);
  float x = t - float(span);
#else
  int span = clamp(int(floor(t + 0.5)), 0, n - 1);
  float x = t - (float(span) - 0.5);
#endif
  first = span - (ORDER - 1) / 2;
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

// Exact D at index point p: ORDER³ texelFetch.
float spline_value(vec3 p) {
  int fx, fy, fz;
  float wx[ORDER], wy[ORDER], wz[ORDER], d[ORDER];
  axis_basis(p.x, u_dims.x, fx, wx, d);
  axis_basis(p.y, u_dims.y, fy, wy, d);
  axis_basis(p.z, u_dims.z, fz, wz, d);
  float sum = 0.0;
  for (int c = 0; c < ORDER; ++c) {
    int iz = clamp(fz + c, 0, u_dims.z - 1);
    float sy = 0.0;
    for (int b = 0; b < ORDER; ++b) {
      int iy = clamp(fy + b, 0, u_dims.y - 1);
      float sx = 0.0;
      for (int a = 0; a < ORDER; ++a)
        sx += wx[a] * texelFetch(u_controls, ivec3(clamp(fx + a, 0, u_dims.x - 1), iy, iz), 0).r;
      sy += wy[b] * sx;
    }
    sum += wz[c] * sy;
  }
  return sum;
}

// Fast D at index point p from GL_LINEAR fetches (error bound in the header).
#if ORDER == 2
float fast_value(vec3 p) {
  vec3 n = vec3(u_dims);
  return textureLod(u_controls, (clamp(p, vec3(0.0), n - 1.0) + 0.5) / n, 0.0).r;
}
#else
// One axis: weights g of the two fetches and their texture coordinates h.
void fast_axis(float t, int n, out vec2 g, out vec2 h) {
  int first;
  float w[ORDER], dw[ORDER];
  axis_basis(t, n, first, w, dw);
#if ORDER == 3
  g = vec2(w[0] + w[1], w[2]);
  h = vec2(float(first) + w[1] / g.x, float(first + 2));
#else
  g = vec2(w[0] + w[1], w[2] + w[3]);
  h = vec2(float(first) + w[1] / g.x, float(first + 2) + w[3] / g.y);
#endif
  h = (h + 0.5) / float(n);
}

float fast_value(vec3 p) {
  vec2 gx, hx, gy, hy, gz, hz;
  fast_axis(p.x, u_dims.x, gx, hx);
  fast_axis(p.y, u_dims.y, gy, hy);
  fast_axis(p.z, u_dims.z, gz, hz);
  float sum = 0.0;
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < 2; ++b) {
      float row = gx.x * textureLod(u_controls, vec3(hx.x, hy[b], hz[c]), 0.0).r +
                  gx.y * textureLod(u_controls, vec3(hx.y, hy[b], hz[c]), 0.0).r;
      sum += gz[c] * gy[b] * row;
    }
  return sum;
}
#endif

// The pixel's ray (gl_FragCoord) in index space: origin on the near plane, unit direction towards NDC depth 0, both
// built in view space (where they are small, so their difference keeps its precision), clipped to the grid box
// [0, n−1]³ and to s ≥ 0: entry point and length (index units). False when the ray misses the box.
bool pixel_ray_in_grid(out vec3 entry, out vec3 u, out float len) {
  vec2 ndc = 2.0 * (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw - 1.0;
  vec4 pn = u_inv_proj * vec4(ndc, -1.0, 1.0);
  vec4 pm = u_inv_proj * vec4(ndc, 0.0, 1.0);
  pn /= pn.w;
  pm /= pm.w;
  vec3 o = (u_view_to_index * vec4(pn.xyz, 1.0)).xyz;
  u = normalize(mat3(u_view_to_index) * (pm.xyz - pn.xyz));
  vec3 box = vec3(u_dims - 1);
  float s_lo = 0.0, s_hi = 3.0e38;
  entry = o;
  len = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (u[a] == 0.0) {
      if (o[a] < 0.0 || o[a] > box[a]) return false;
      continue;
    }
    float s0 = -o[a] / u[a], s1 = (box[a] - o[a]) / u[a];
    s_lo = max(s_lo, min(s0, s1));
    s_hi = min(s_hi, max(s0, s1));
  }
  if (!(s_lo <= s_hi)) return false;
  entry = o + s_lo * u;
  len = s_hi - s_lo;
  return true;
}

// Linear RGB → sRGB encoding (the framebuffer is plain RGBA8 holding sRGB values, as the mesh shader writes).
vec3 linear_to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
