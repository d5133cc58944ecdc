#version 430 core
// World-space triangle meshes (world_mesh is already in world space; no model matrix).
// Attribute locations are shared with the GLSL FFD vertex path: 0 position, 1 normal, 2 (u,v,w).
// Variant OUTLINE: the vertex is pushed outwards along its screen-space normal by u_outline_px pixels (the
// selection outline is that enlarged silhouette, masked by the stencil of the object itself).
// Variant DEPTH_PULL: the vertex is drawn moved towards the eye by the fraction u_depth_pull of its distance —
// same pixel (it slides along its own view ray), slightly nearer depth — so an overlay lying on a surface (the
// contact surface S(u,v) = F(u,v,0) on the object it was fitted to) wins the depth test without z-fighting.
// Variant FFD (seed §4.2.1 single phase): position and normal are evaluated here from the vertex's
// parameters a_param (location 2) and its rest normal (location 1, world rest space) through the control lattice
// in SSBOs 4/5 (ffd_eval.glsl; ORDER_U/V/W, FFD_NORMALS), at a_param + u_param_offset (seed §4.5 animation).
// gpu::GlslVertexFfdEvaluator draws with it, and captures v_world / v_normal by transform feedback for read-back.
// Variant MATERIAL (Material shading): the texture coordinate a_uv (location 3; TriMesh::uvs, (0,0) without) is
// passed on unchanged — it rides along whatever deformation moved the position.
layout(location = 0) in vec3 a_position;  // world units (unused by FFD)
layout(location = 1) in vec3 a_normal;    // unit (FFD: the rest normal)
#ifdef FFD
#include "ffd_eval.glsl"
layout(location = 2) in vec3 a_param;  // (u,v,w), parameter domain
uniform vec3 u_param_offset;           // parameter units
#endif
uniform mat4 u_view_proj;
out vec3 v_world;
out vec3 v_normal;
#ifdef MATERIAL
layout(location = 3) in vec2 a_uv;
out vec2 v_uv;
#endif
#ifdef OUTLINE
#include "outline.glsl"
#endif
#ifdef DEPTH_PULL
uniform vec3 u_eye;          // world units
uniform float u_depth_pull;  // fraction of the eye distance, e.g. 0.003
#endif
void main() {
#ifdef FFD
  vec3 position, normal;
  ffd_eval(a_param + u_param_offset, a_normal, position, normal);
#else
  vec3 position = a_position;
  vec3 normal = a_normal;
#endif
#ifdef DEPTH_PULL
  vec4 clip = u_view_proj * vec4(mix(position, u_eye, u_depth_pull), 1.0);
#else
  vec4 clip = u_view_proj * vec4(position, 1.0);
#endif
#ifdef OUTLINE
  clip = outline_push(clip, u_view_proj, normal);
#endif
  v_world = position;
  v_normal = normal;
#ifdef MATERIAL
  v_uv = a_uv;
#endif
  gl_Position = clip;
}
