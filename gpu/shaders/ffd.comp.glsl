#version 430 core
// GLSL compute FFD: one invocation per vertex, x' = F(uvw + u_param_offset) and, with FFD_NORMALS,
// n' ∝ cof(J_F·A)·n (ffd_eval.glsl). Inputs and outputs are tightly packed float arrays, element 3·i + c, so the
// outputs can be the position / normal buffers the renderer draws (gpu::MeshBuffers, attributes 0 and 1).
// Groups are laid out 2D (x ≤ 65535) to cover any vertex count; invocations past u_vertex_count return.
// Defines: LOCAL_SIZE (default 128), ORDER_U/V/W, FFD_NORMALS.
#ifndef LOCAL_SIZE
#define LOCAL_SIZE 128
#endif
layout(local_size_x = LOCAL_SIZE) in;
#include "ffd_eval.glsl"
layout(std430, binding = 0) readonly buffer FfdParams { float ffd_params[]; };  // #V × 3 (u,v,w)
layout(std430, binding = 2) writeonly buffer FfdOutPositions { float ffd_out_positions[]; };  // #V × 3 world units
#ifdef FFD_NORMALS
layout(std430, binding = 1) readonly buffer FfdRestNormals { float ffd_rest_normals[]; };     // #V × 3 unit
layout(std430, binding = 3) writeonly buffer FfdOutNormals { float ffd_out_normals[]; };      // #V × 3 unit
#endif
uniform vec3 u_param_offset;  // parameter units, added to every vertex's (u,v,w)
uniform uint u_vertex_count;  // #V

void main() {
  uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * uint(LOCAL_SIZE) + gl_LocalInvocationID.x;
  if (i >= u_vertex_count) return;
  uint b = 3u * i;
  vec3 p = vec3(ffd_params[b], ffd_params[b + 1u], ffd_params[b + 2u]) + u_param_offset;
#ifdef FFD_NORMALS
  vec3 n_rest = vec3(ffd_rest_normals[b], ffd_rest_normals[b + 1u], ffd_rest_normals[b + 2u]);
#else
  vec3 n_rest = vec3(0.0);
#endif
  vec3 position, normal;
  ffd_eval(p, n_rest, position, normal);
  ffd_out_positions[b] = position.x;
  ffd_out_positions[b + 1u] = position.y;
  ffd_out_positions[b + 2u] = position.z;
#ifdef FFD_NORMALS
  ffd_out_normals[b] = normal.x;
  ffd_out_normals[b + 1u] = normal.y;
  ffd_out_normals[b + 2u] = normal.z;
#endif
}
