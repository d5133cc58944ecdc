#version 430 core
// Studio shading: key headlight + hemisphere ambient + soft specular + a little rim, in linear RGB, then
// tone-mapped and sRGB-encoded here (the framebuffer is plain RGBA8).
// Variant FLAT_COLOR: writes u_flat_color (display values) unlit — selection outline and wireframe overlay
// (with ALPHA_MASK: discarded where the base colour's alpha is below u_alpha_cutoff).
// Variant TRANSLUCENT: a see-through tinted sheet (the contact surface): u_tint (display values, alpha) lightly
// shaded by the facing ratio, and more opaque at grazing angles so its folds read; both faces alike.
// Variant MATERIAL (Material shading, glTF 2.0 §3.9 metallic-roughness, viewport approximation): base colour factor ×
// texture (sRGB textures decode in the sampler), the normal map in a per-fragment cotangent frame built from screen
// derivatives of v_world and v_uv (Schüler 2013, "Normal Mapping Without Precomputed Tangents": no tangent
// attribute), occlusion on the ambient term, metallic tinting the specular and darkening the diffuse, roughness
// widening the highlight, emissive added; the same studio lights as Solid so the two read alike. Alpha: u_alpha_mode
// 1 (MASK) discards below u_alpha_cutoff, 2 (BLEND) writes alpha for a back-to-front blended pass, 0 is opaque.
// Texture coordinates follow glTF: (0,0) is the image's first (top) row, as MaterialImage::rgba8 is uploaded.
// u_flat_normal = 1 (default variant): the face normal from the screen derivatives of v_world replaces the
// interpolated vertex normal — for cut surfaces (DFFD caps, incision walls, kMaterialInside), whose vertices are
// shared with the surface and carry the surface's normals.
in vec3 v_world;
in vec3 v_normal;
out vec4 o_color;
#ifdef FLAT_COLOR
uniform vec4 u_flat_color;
#ifdef ALPHA_MASK
// With MATERIAL + OUTLINE: the selection outline of an alpha-MASK range keeps its cut-out texels open.
in vec2 v_uv;
uniform sampler2D u_base_tex;  // unit 0
uniform float u_base_alpha;    // baseColorFactor alpha
uniform float u_alpha_cutoff;
#endif
void main() {
#ifdef ALPHA_MASK
  if (u_base_alpha * texture(u_base_tex, v_uv).a < u_alpha_cutoff) discard;
#endif
  o_color = u_flat_color;
}
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
uniform vec3 u_eye;         // world units
uniform vec3 u_key_dir;     // unit, towards the key light (near the view direction: a headlight)
uniform float u_highlight;  // 0..1, selection tint
uniform int u_flat_normal;  // 1: faceted (face normal from dFdx/dFdy of v_world), 0: interpolated v_normal
vec3 linear_to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
// The studio lights on a surface of linear `albedo` with unit normal `n` facing the viewer (`back`: it was flipped),
// `spec_color` and `shininess` of the highlight, `ao` on the ambient term; returns display (sRGB) values.
vec3 studio(vec3 albedo, vec3 n, vec3 v, bool back, vec3 spec_color, float shininess, float ao, vec3 emissive) {
  albedo = mix(albedo, vec3(1.0, 0.72, 0.35), u_highlight * 0.25);
  float wrap = 0.25;
  float key = max((dot(n, u_key_dir) + wrap) / (1.0 + wrap), 0.0);
  vec3 sky = vec3(0.62, 0.68, 0.78);
  vec3 ground = vec3(0.26, 0.23, 0.21);
  vec3 ambient = mix(ground, sky, 0.5 + 0.5 * n.y);
  vec3 h = normalize(u_key_dir + v);
  vec3 spec = pow(max(dot(n, h), 0.0), shininess) * spec_color;
  float rim = pow(1.0 - max(dot(n, v), 0.0), 3.0) * 0.22;
  vec3 c = albedo * (0.30 * ao * ambient + 0.80 * key * key) + spec + rim * sky;
  if (back) c *= vec3(0.55, 0.5, 0.5);
  c += emissive;
  c = c / (1.0 + 0.35 * max(max(c.r, c.g), c.b));  // gentle highlight roll-off
  return linear_to_srgb(c * 1.25);
}
#ifdef MATERIAL
in vec2 v_uv;
uniform vec4 u_base_color;          // baseColorFactor, linear RGBA
uniform sampler2D u_base_tex;       // unit 0, sRGB (white when absent)
uniform sampler2D u_mr_tex;         // unit 1, linear: G roughness, B metallic (white when absent)
uniform sampler2D u_normal_tex;     // unit 2, linear tangent-space normal
uniform sampler2D u_occlusion_tex;  // unit 3, linear: R occlusion (white when absent)
uniform sampler2D u_emissive_tex;   // unit 4, sRGB (white when absent)
uniform float u_metallic, u_roughness;
uniform int u_has_normal_tex;
uniform float u_normal_scale, u_occlusion_strength;
uniform vec3 u_emissive;            // emissiveFactor, linear RGB
uniform int u_alpha_mode;           // 0 OPAQUE, 1 MASK, 2 BLEND
uniform float u_alpha_cutoff;
// Perturbs unit normal `n` by the tangent-space normal `t` in the cotangent frame of (p, uv) at this fragment.
vec3 perturb_normal(vec3 n, vec3 p, vec2 uv, vec3 t) {
  vec3 dp1 = dFdx(p), dp2 = dFdy(p);
  vec2 duv1 = dFdx(uv), duv2 = dFdy(uv);
  vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
  vec3 T = dp2perp * duv1.x + dp1perp * duv2.x;
  vec3 B = dp2perp * duv1.y + dp1perp * duv2.y;
  float m = max(dot(T, T), dot(B, B));
  if (!(m > 1e-30)) return n;  // no uv gradient here (degenerate mapping)
  float invmax = inversesqrt(m);
  vec3 r = mat3(T * invmax, B * invmax, n) * t;
  float len = length(r);
  return len > 1e-12 ? r / len : n;
}
void main() {
  vec4 base = u_base_color * texture(u_base_tex, v_uv);
  if (u_alpha_mode == 1 && base.a < u_alpha_cutoff) discard;
  vec3 n = normalize(u_flat_normal != 0 ? cross(dFdx(v_world), dFdy(v_world)) : v_normal);  // 1: textured caps
  vec3 v = normalize(u_eye - v_world);
  bool back = dot(n, v) < 0.0;
  if (back) n = -n;
  if (u_has_normal_tex != 0) {
    vec3 t = texture(u_normal_tex, v_uv).xyz * 2.0 - 1.0;
    t.xy *= u_normal_scale;
    // glTF's normal maps use +Y up in uv space with v growing downwards in the image: the bitangent flips.
    t.y = -t.y;
    n = perturb_normal(n, v_world, v_uv, t);
  }
  vec4 mr = texture(u_mr_tex, v_uv);
  float metallic = clamp(u_metallic * mr.b, 0.0, 1.0);
  float roughness = clamp(u_roughness * mr.g, 0.04, 1.0);
  float ao = mix(1.0, texture(u_occlusion_tex, v_uv).r, u_occlusion_strength);
  // No environment to reflect: metals keep part of their colour as diffuse so they read (not black).
  float shininess = mix(256.0, 6.0, sqrt(roughness));
  vec3 spec_color = mix(vec3(0.22), base.rgb, metallic) * (1.0 - 0.6 * roughness);
  vec3 albedo = base.rgb * mix(1.0, 0.45, metallic);
  vec3 emissive = u_emissive * texture(u_emissive_tex, v_uv).rgb;
  vec3 c = studio(albedo, n, v, back, spec_color, shininess, ao, emissive);
  o_color = vec4(c, u_alpha_mode == 2 ? base.a : 1.0);
}
#else
uniform vec3 u_albedo;  // linear RGB
void main() {
  vec3 n = normalize(u_flat_normal != 0 ? cross(dFdx(v_world), dFdy(v_world)) : v_normal);
  vec3 v = normalize(u_eye - v_world);
  bool back = dot(n, v) < 0.0;  // robust two-sided lighting even where the winding is inconsistent
  if (back) n = -n;
  o_color = vec4(studio(u_albedo, n, v, back, vec3(0.22), 56.0, 1.0, vec3(0.0)), 1.0);
}
#endif
#endif
