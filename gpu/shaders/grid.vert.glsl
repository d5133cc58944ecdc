#version 430 core
// Full-screen triangle carrying each pixel's view ray as its near- and far-plane points (world units); the
// fragment shader intersects the ray with the ground plane y = 0.
uniform mat4 u_inv_view_proj;
out vec3 v_near;
out vec3 v_far;
vec3 unproject(vec2 ndc, float z) {
  vec4 p = u_inv_view_proj * vec4(ndc, z, 1.0);
  return p.xyz / p.w;
}
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  v_near = unproject(p, -1.0);
  v_far = unproject(p, 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
