#version 430 core
// The selection outline's vertex push, included by the OUTLINE variants of mesh.vert and ddm.vert: `clip` moved
// outwards along the screen-space direction of the world normal `n` by u_outline_px pixels, so the enlarged
// silhouette drawn where the object itself is not (stencil) reads as an outline of constant width.
// A normal facing the eye projects to (almost) nothing — a flat card seen face-on would get no outline — so as its
// projection shrinks the push turns to the direction away from the object's centre on screen (the card grows);
// silhouette normals, whose projection is of the order of the projection's scale, are not affected.
uniform vec2 u_viewport;        // pixels
uniform float u_outline_px;     // pixels
uniform vec3 u_outline_center;  // world units: centre of the object's bounds

vec4 outline_push(vec4 clip, mat4 view_proj, vec3 n) {
  vec2 s = (view_proj * vec4(n, 0.0)).xy;
  float len = length(s);
  vec4 c = view_proj * vec4(u_outline_center, 1.0);
  vec2 radial = (clip.w != 0.0 && c.w != 0.0) ? clip.xy / clip.w - c.xy / c.w : vec2(0.0);
  float rlen = length(radial);
  float along_normal = min(len / 0.25, 1.0);  // 1 from about 6° off facing the eye
  vec2 dir = (len > 1e-12 ? s / len : vec2(0.0)) * along_normal +
             (rlen > 1e-9 ? radial / rlen : vec2(0.0)) * (1.0 - along_normal);
  float dlen = length(dir);
  if (dlen > 1e-6) clip.xy += (dir / dlen) * (2.0 * u_outline_px / u_viewport) * clip.w;
  return clip;
}
