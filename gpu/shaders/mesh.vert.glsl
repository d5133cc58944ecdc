#version 430 core
// World-space triangle meshes (world_mesh is already in world space; no model matrix).
// Attribute locations are shared with the GLSL FFD vertex path (issue 3): 0 position, 1 normal, 2 (u,v,w).
// Variant OUTLINE: the vertex is pushed outwards along its screen-space normal by u_outline_px pixels (the
// selection outline is that enlarged silhouette, masked by the stencil of the object itself).
// Variant DEPTH_PULL: the vertex is drawn moved towards the eye by the fraction u_depth_pull of its distance —
// same pixel (it slides along its own view ray), slightly nearer depth — so an overlay lying on a surface (the
// contact surface S(u,v) = F(u,v,0) on the object it was fitted to) wins the depth test without z-fighting.
layout(location = 0) in vec3 a_position;  // world units
layout(location = 1) in vec3 a_normal;    // unit
uniform mat4 u_view_proj;
out vec3 v_world;
out vec3 v_normal;
#ifdef OUTLINE
uniform vec2 u_viewport;    // pixels
uniform float u_outline_px; // pixels
#endif
#ifdef DEPTH_PULL
uniform vec3 u_eye;          // world units
uniform float u_depth_pull;  // fraction of the eye distance, e.g. 0.003
#endif
void main() {
#ifdef DEPTH_PULL
  vec4 clip = u_view_proj * vec4(mix(a_position, u_eye, u_depth_pull), 1.0);
#else
  vec4 clip = u_view_proj * vec4(a_position, 1.0);
#endif
#ifdef OUTLINE
  vec2 n = (u_view_proj * vec4(a_normal, 0.0)).xy;
  float len = length(n);
  if (len > 1e-12) clip.xy += (n / len) * (2.0 * u_outline_px / u_viewport) * clip.w;
#endif
  v_world = a_position;
  v_normal = a_normal;
  gl_Position = clip;
}
