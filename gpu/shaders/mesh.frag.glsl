#version 430 core
// Studio shading: key headlight + hemisphere ambient + soft specular + a little rim, in linear RGB, then
// tone-mapped and sRGB-encoded here (the framebuffer is plain RGBA8).
// Variant FLAT_COLOR: writes u_flat_color (display values) unlit — selection outline and wireframe overlay.
// Variant TRANSLUCENT: a see-through tinted sheet (the contact surface): u_tint (display values, alpha) lightly
// shaded by the facing ratio, and more opaque at grazing angles so its folds read; both faces alike.
// u_flat_normal = 1 (default variant): the face normal from the screen derivatives of v_world replaces the
// interpolated vertex normal — for cut surfaces (DFFD caps, incision walls, kMaterialInside), whose vertices are
// shared with the surface and carry the surface's normals.
in vec3 v_world;
in vec3 v_normal;
out vec4 o_color;
#ifdef FLAT_COLOR
uniform vec4 u_flat_color;
void main() { o_color = u_flat_color; }
#elif defined(TRANSLUCENT)
uniform vec4 u_tint;  // display values, alpha at normal incidence
uniform vec3 u_eye;   // world units
void main() {
  float facing = abs(dot(normalize(v_normal), normalize(u_eye - v_world)));
  vec3 c = u_tint.rgb * (0.70 + 0.30 * facing) + vec3(0.10) * pow(facing, 24.0);
  float a = u_tint.a * mix(1.8, 1.0, smoothstep(0.0, 0.6, facing));
  o_color = vec4(c, clamp(a, 0.0, 1.0));
}
#else
uniform vec3 u_albedo;      // linear RGB
uniform vec3 u_eye;         // world units
uniform vec3 u_key_dir;     // unit, towards the key light (near the view direction: a headlight)
uniform float u_highlight;  // 0..1, selection tint
uniform int u_flat_normal;  // 1: faceted (face normal from dFdx/dFdy of v_world), 0: interpolated v_normal
vec3 linear_to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
void main() {
  vec3 n = normalize(u_flat_normal != 0 ? cross(dFdx(v_world), dFdy(v_world)) : v_normal);
  vec3 v = normalize(u_eye - v_world);
  bool back = dot(n, v) < 0.0;  // robust two-sided lighting even where the winding is inconsistent
  if (back) n = -n;
  vec3 albedo = mix(u_albedo, vec3(1.0, 0.72, 0.35), u_highlight * 0.25);
  float wrap = 0.25;
  float key = max((dot(n, u_key_dir) + wrap) / (1.0 + wrap), 0.0);
  vec3 sky = vec3(0.62, 0.68, 0.78);
  vec3 ground = vec3(0.26, 0.23, 0.21);
  vec3 ambient = mix(ground, sky, 0.5 + 0.5 * n.y);
  vec3 h = normalize(u_key_dir + v);
  float spec = pow(max(dot(n, h), 0.0), 56.0) * 0.22;
  float rim = pow(1.0 - max(dot(n, v), 0.0), 3.0) * 0.22;
  vec3 c = albedo * (0.30 * ambient + 0.80 * key * key) + vec3(spec) + rim * sky;
  if (back) c *= vec3(0.55, 0.5, 0.5);
  c = c / (1.0 + 0.35 * max(max(c.r, c.g), c.b));  // gentle highlight roll-off
  o_color = vec4(linear_to_srgb(c * 1.25), 1.0);
}
#endif
