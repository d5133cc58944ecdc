#version 430 core
// The grid box [0, nx−1] × [0, ny−1] × [0, nz−1] of a volume (index space) as 12 triangles, CCW seen from outside
// in index space: 36 vertices from gl_VertexID, no attributes (draw with an empty vertex array). The iso-surface ray
// caster (volume_iso.frag.glsl) rasterises its back faces, so it also runs with the eye inside the box.
uniform vec3 u_box_max;        // (nx−1, ny−1, nz−1), index units
uniform mat4 u_index_to_clip;  // projection · view · index_to_world
// Corner c of the unit cube is (c & 1, (c >> 1) & 1, (c >> 2) & 1).
const int kCorners[36] = int[36](0, 6, 2, 0, 4, 6, 1, 3, 7, 1, 7, 5, 0, 5, 4, 0, 1, 5, 2, 6, 7, 2, 7, 3, 0, 3, 1, 0, 2,
                                 3, 4, 5, 7, 4, 7, 6);
void main() {
  int c = kCorners[gl_VertexID % 36];
  vec3 corner = vec3(float(c & 1), float((c >> 1) & 1), float((c >> 2) & 1));
  gl_Position = u_index_to_clip * vec4(corner * u_box_max, 1.0);
}
