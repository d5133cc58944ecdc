#version 430 core
// Coloured world-space lines and points (lattice, contact samples). Variant SCREEN_SPACE: positions are
// viewport pixels (x right, y down, top-left origin) — the sketched stroke.
#ifdef SCREEN_SPACE
layout(location = 0) in vec2 a_position;  // pixels
uniform vec2 u_viewport;                  // pixels
#else
layout(location = 0) in vec3 a_position;  // world units
uniform mat4 u_view_proj;
uniform float u_point_px;                 // point diameter, pixels
#endif
layout(location = 1) in vec4 a_color;     // display values, alpha
uniform float u_alpha;                    // multiplies a_color.a (hidden parts are drawn faint)
out vec4 v_color;
void main() {
#ifdef SCREEN_SPACE
  vec2 ndc = vec2(2.0 * a_position.x / u_viewport.x - 1.0, 1.0 - 2.0 * a_position.y / u_viewport.y);
  gl_Position = vec4(ndc, 0.0, 1.0);
#else
  gl_Position = u_view_proj * vec4(a_position, 1.0);
  gl_PointSize = u_point_px;
#endif
  v_color = vec4(a_color.rgb, a_color.a * u_alpha);
}
