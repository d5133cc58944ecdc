#version 430 core
// Full-screen triangle (no vertex buffer: draw 3 vertices with an empty VAO). v_t = 0 at the bottom, 1 at the top.
out float v_t;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));  // (0,0) (2,0) (0,2)
  v_t = p.y;
  gl_Position = vec4(p * 2.0 - 1.0, 1.0, 1.0);
}
