#version 430 core
// Coloured world-space lines and points (lattice, contact samples). Variant SCREEN_SPACE: positions are
// viewport pixels (x right, y down, top-left origin) — the sketched stroke. Variant DEPTH_PULL (world space
// only): as in mesh.vert.glsl, drawn moved towards the eye by the fraction u_depth_pull of its distance (same
// pixel, nearer depth) — iso-lines of the contact surface lying on the object they were fitted to. Variant
// SCREEN_DEPTH (with SCREEN_SPACE): a_position.z is the normalized device depth in [-1, 1], so thick strokes built in
// pixels are depth-tested (volume silhouettes, gpu/view/silhouette_strokes.h).
#if defined(SCREEN_SPACE) && defined(SCREEN_DEPTH)
layout(location = 0) in vec3 a_position;  // pixels, NDC depth
uniform vec2 u_viewport;                  // pixels
#elif defined(SCREEN_SPACE)
layout(location = 0) in vec2 a_position;  // pixels
uniform vec2 u_viewport;                  // pixels
#else
layout(location = 0) in vec3 a_position;  // world units
uniform mat4 u_view_proj;
uniform float u_point_px;                 // point diameter, pixels
#ifdef DEPTH_PULL
uniform vec3 u_eye;                       // world units
uniform float u_depth_pull;               // fraction of the eye distance
#endif
#endif
layout(location = 1) in vec4 a_color;     // display values, alpha
uniform float u_alpha;                    // multiplies a_color.a (hidden parts are drawn faint)
out vec4 v_color;
void main() {
#ifdef SCREEN_SPACE
  vec2 ndc = vec2(2.0 * a_position.x / u_viewport.x - 1.0, 1.0 - 2.0 * a_position.y / u_viewport.y);
#ifdef SCREEN_DEPTH
  gl_Position = vec4(ndc, a_position.z, 1.0);
#else
  gl_Position = vec4(ndc, 0.0, 1.0);
#endif
#elif defined(DEPTH_PULL)
  gl_Position = u_view_proj * vec4(mix(a_position, u_eye, u_depth_pull), 1.0);
  gl_PointSize = u_point_px;
#else
  gl_Position = u_view_proj * vec4(a_position, 1.0);
  gl_PointSize = u_point_px;
#endif
  v_color = vec4(a_color.rgb, a_color.a * u_alpha);
}
