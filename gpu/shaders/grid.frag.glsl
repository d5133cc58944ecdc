#version 430 core
// Ground grid on y = 0: anti-aliased minor/major lines (fwidth), x axis red and z axis blue, fading with the
// distance from the eye and at grazing angles. Writes the plane's depth so meshes occlude it correctly.
in vec3 v_near;
in vec3 v_far;
uniform mat4 u_view_proj;
uniform vec3 u_eye;          // world units
uniform float u_cell;        // minor cell size, world units (major lines every 10 cells)
uniform float u_fade_dist;   // world units: fully faded beyond this distance from the eye
uniform vec3 u_line_color;   // display values
out vec4 o_color;
float grid_lines(vec2 coord, float width_px) {
  vec2 d = fwidth(coord);
  vec2 g = abs(fract(coord - 0.5) - 0.5) / max(d, vec2(1e-6));
  float line = min(g.x, g.y);
  return 1.0 - clamp(line / width_px, 0.0, 1.0);
}
void main() {
  vec3 dir = v_far - v_near;
  if (abs(dir.y) < 1e-12) discard;
  float t = -v_near.y / dir.y;
  if (t <= 0.0 || t >= 1.0) discard;
  vec3 p = v_near + t * dir;
  vec4 clip = u_view_proj * vec4(p, 1.0);
  gl_FragDepth = clamp(clip.z / clip.w * 0.5 + 0.5, 0.0, 1.0);

  float dist = length(p - u_eye);
  vec2 c = p.xz / u_cell;
  // Minor lines fade out first (level of detail), so the distance never turns into moiré.
  float minor = grid_lines(c, 1.0) * 0.2 * (1.0 - smoothstep(0.25 * u_fade_dist, 0.75 * u_fade_dist, dist));
  float major = grid_lines(c / 10.0, 1.25) * 0.45;
  float a = max(minor, major);
  vec3 color = u_line_color;
  vec2 dw = fwidth(p.xz);
  float ax_z = 1.0 - clamp(abs(p.z) / max(dw.y, 1e-6) / 1.5, 0.0, 1.0);  // line z = 0: the x axis
  float ax_x = 1.0 - clamp(abs(p.x) / max(dw.x, 1e-6) / 1.5, 0.0, 1.0);  // line x = 0: the z axis
  if (ax_z > 0.0) { color = mix(color, vec3(0.85, 0.32, 0.32), ax_z); a = max(a, ax_z * 0.8); }
  if (ax_x > 0.0) { color = mix(color, vec3(0.32, 0.5, 0.9), ax_x); a = max(a, ax_x * 0.8); }

  float fade = 1.0 - smoothstep(0.25 * u_fade_dist, u_fade_dist, dist);
  float grazing = smoothstep(0.02, 0.25, abs(normalize(dir).y));
  a *= fade * grazing;
  if (a <= 0.002) discard;
  o_color = vec4(color, a);
}
