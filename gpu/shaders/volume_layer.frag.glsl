#version 430 core
// Composites the volumes' ray-cast layer (gpu/render/renderer_volume.h) into the frame, with background.vert.glsl's
// full-screen triangle: colour and depth of the full-resolution layer where it has been refined (window rows
// gl_FragCoord.y ≥ u_refined_from), else of the low-resolution preview (nearest texel); pixels no ray hit (depth 1)
// are discarded. The colours are the ray caster's sRGB-encoded output, copied as they are.
layout(binding = 0) uniform sampler2D u_color;
layout(binding = 1) uniform sampler2D u_depth;
layout(binding = 2) uniform sampler2D u_preview_color;
layout(binding = 3) uniform sampler2D u_preview_depth;
uniform float u_refined_from;  // window row (pixels from the bottom) from which the full layer holds the result
uniform vec2 u_viewport;       // pixels
out vec4 o_color;
void main() {
  bool full = gl_FragCoord.y >= u_refined_from;
  vec2 uv = gl_FragCoord.xy / u_viewport;
  float depth = full ? texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r : texture(u_preview_depth, uv).r;
  if (depth >= 1.0) discard;
  o_color = full ? texelFetch(u_color, ivec2(gl_FragCoord.xy), 0) : texture(u_preview_color, uv);
  gl_FragDepth = depth;
}
