#version 430 core
// The selection outline's vertex push, included by the OUTLINE variants of mesh.vert and ddm.vert: `clip` moved
// outwards along the screen-space direction of the world normal `n` by u_outline_px pixels, so the enlarged
// silhouette drawn where the object itself is not (stencil) reads as an outline of constant width.
uniform vec2 u_viewport;    // pixels
uniform float u_outline_px; // pixels

vec4 outline_push(vec4 clip, mat4 view_proj, vec3 n) {
  vec2 s = (view_proj * vec4(n, 0.0)).xy;
  float len = length(s);
  if (len > 1e-12) clip.xy += (s / len) * (2.0 * u_outline_px / u_viewport) * clip.w;
  return clip;
}
