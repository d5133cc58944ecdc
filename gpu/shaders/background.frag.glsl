#version 430 core
// Flat vertical gradient. Colours are display (sRGB-encoded) values, as ViewOptions documents them.
in float v_t;
uniform vec3 u_top;
uniform vec3 u_bottom;
out vec4 o_color;
void main() {
  // A slight ease keeps the horizon band calm; the gradient is interpolated in display space on purpose.
  float t = smoothstep(0.0, 1.0, clamp(v_t, 0.0, 1.0));
  o_color = vec4(mix(u_bottom, u_top, t), 1.0);
}
