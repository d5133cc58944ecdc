#version 430 core
// Variant ROUND_POINTS: point sprites cut to discs with a dark rim.
in vec4 v_color;
out vec4 o_color;
void main() {
#ifdef ROUND_POINTS
  float r = length(gl_PointCoord - 0.5) * 2.0;
  if (r > 1.0) discard;
  o_color = vec4(mix(v_color.rgb, v_color.rgb * 0.25, smoothstep(0.55, 0.8, r)), v_color.a);
#else
  o_color = v_color;
#endif
}
