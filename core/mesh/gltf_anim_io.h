// trispline::core animated glTF 2.0 (tinygltf): a recorded sequence of frames as morph targets (anim.record's
// animation.glb, seed §2.4.3), and a reader used by tests and tools to check what was written.
//
//   MorphAnimationBuilder        add_frame() per recorded frame, write_glb() at the end; write_piece() /
//                                read_piece() / append_piece() join recordings split by frames (a render farm)
//   read_morph_animation_info    counts: meshes, morph targets, keyframes, interpolation, duration
//   read_morph_frame_positions   one mesh's vertex positions at one frame (base + that frame's target)
//
// Layout of the file (Blender's glTF importer turns it into shape keys with keyed values):
//   * per object one node (named by the object id, no transform: positions are world units) and one mesh with one
//     TRIANGLES primitive; its POSITION / NORMAL / TEXCOORD_0 / indices are the FIRST frame's mesh (as write_glb);
//     an object with materials (GltfNode::materials) or cut surfaces gets one primitive per material slot its faces
//     use instead (and one for its kMaterialInside faces, GltfNode::inside_material or "<name>.inside" of
//     inside_color), sharing the vertex accessors and morph targets, with the materials, their textures and images
//     written as write_glb writes them (pieces, write_piece, keep them too);
//   * an object whose geometry changes in any frame gets one morph target per following frame (#frames − 1 targets,
//     POSITION and NORMAL deltas relative to the first frame, float32; a frame equal to the first has zero deltas),
//     mesh.weights all 0 and mesh.extras.targetNames = ["frame_NNNN", ...] (Blender names the shape keys so);
//     an object whose geometry never changes gets no targets;
//   * an object whose topology changes (vertex count or triangles: a DFFD split opening, seed Fig. 6.10) is split into
//     segments, runs of frames with one topology: its node has no mesh but one child per segment, named
//     "<object>/frames_NNNN-MMMM" (extras.frames = [NNNN, MMMM], timeline frames), each with the segment's first mesh
//     and morph targets for the segment's other frames, and a STEP "scale" channel that shows it (1) on its frames and
//     hides it (0) elsewhere (its rest scale is that of the recording's first frame) — Blender imports these as an
//     object per segment with keyed scale;
//   * when some node is animated: one animation "recording" whose channels ("weights" per morphing mesh node,
//     "scale" per segment node) all share one input (#frames times k/fps seconds, k = 0..#frames−1), interpolation
//     STEP; a weights output holds #frames × #targets weights: at key k the target of frame k is 1, all others 0.
// Memory: the builder keeps each segment's first mesh and per following frame 6 floats per vertex.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/gltf_io.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

// Frames one recording may hold: a timeline runs from frame 0 to at most 100000 (anim.timeline).
inline constexpr int kMaxRecordedFrames = 100001;
// Bytes an animation.glb may take. A morphing object writes #frames − 1 targets of 24 bytes a vertex and #frames ×
// (#frames − 1) weights, so the file grows with the square of the frames; write_glb refuses past this (the .glb
// header counts in 32 bits, and tinygltf holds the file about three times over while writing it).
inline constexpr std::uint64_t kMaxAnimationGlbBytes = std::uint64_t(1) << 30;

class MorphAnimationBuilder {
 public:
  // fps: frames per second of the recording (> 0, finite); first_frame: the timeline number of the first frame added
  // (names targets "frame_NNNN"). Throws std::invalid_argument on a bad fps.
  explicit MorphAnimationBuilder(double fps, int first_frame = 0);

  // Adds the next frame: the same objects (names, order) every time; a mesh whose topology differs from the previous
  // frame's starts a new segment (see above). A mesh may be null/empty in every frame (the node then has no mesh).
  // Throws MeshIoError naming the object when the objects differ from the first frame's, a mesh appears or
  // disappears, or a mesh fails validate_mesh; the builder is then unchanged.
  void add_frame(const std::vector<GltfNode>& nodes);
  int frame_count() const { return frames_; }
  // Objects whose geometry changed so far (morph targets, or several segments).
  int animated_objects() const;
  // Segments (runs of frames with one topology) of `object` so far; 0 for an unknown object or one without a mesh.
  int segment_count(const std::string& object) const;

  // Writes the .glb ("<path>.tmp" then renamed). Throws MeshIoError when no frame was added, when the file would
  // take more than kMaxAnimationGlbBytes (checked before anything is built; the message gives both sizes), or when
  // the write fails.
  void write_glb(const std::filesystem::path& path) const;
  // The bytes of binary data write_glb would write (vertices, indices, targets, keys; not the JSON or images).
  std::uint64_t glb_data_bytes() const;

  // Pieces of one recording split by frames (gltf_anim_piece.cpp). A piece is a builder whose first frame is the
  // whole range's first frame (the base) followed by the frames of one chunk, so its morph targets are the deltas one
  // builder over the whole range computes, bit for bit. write_piece stores the builder losslessly (base meshes in
  // double; "<path>.tmp" then renamed); read_piece reads it back. Both throw MeshIoError (a bad or truncated file,
  // or one whose first frame and frame count leave the timeline's 0..kMaxRecordedFrames − 1).
  void write_piece(const std::filesystem::path& path) const;
  static MorphAnimationBuilder read_piece(const std::filesystem::path& path);
  // Appends the frames of `piece` after its first. Joinable when the piece has the same fps and first frame number,
  // the same objects, and every object keeps one topology in both with the same base mesh (exactly): then this
  // builder becomes what adding those frames one by one would make. Returns false, the builder unchanged, otherwise
  // (an object whose topology changes cannot be re-based exactly: record the range in one process instead).
  bool append_piece(const MorphAnimationBuilder& piece);

 private:
  struct Segment {
    int first = 0;                              // index of its first frame in the recording
    int frames = 1;                             // frames it covers
    TriMesh base;                               // its first frame's mesh
    std::vector<std::vector<float>> pos_delta;  // per following frame: #V × 3, or empty = all zero
    std::vector<std::vector<float>> nrm_delta;  // per following frame: #V × 3, or empty = all zero
    bool changed = false;                       // some following frame differs from base
  };
  struct Object {
    std::string name;
    glm::vec3 color{0.8f};
    std::shared_ptr<const MaterialSet> materials;        // the first frame's GltfNode::materials (null: `color`)
    glm::vec3 inside_color{0.62f, 0.10f, 0.08f};         // the first frame's GltfNode::inside_color
    std::shared_ptr<const MaterialSet> inside_material;  // the first frame's GltfNode::inside_material
    std::vector<Segment> segments;                       // empty: no mesh
  };
  double fps_;
  int first_frame_;
  int frames_ = 0;
  std::vector<Object> objects_;
};

struct MorphAnimationInfo {
  struct Mesh {
    std::string name;
    std::size_t vertices = 0;               // POSITION count of the first primitive
    int targets = 0;                        // morph targets of the first primitive
    std::vector<std::string> target_names;  // mesh.extras.targetNames (empty when absent)
  };
  std::vector<Mesh> meshes;  // in file order
  int animations = 0;
  int weight_channels = 0;    // channels with path "weights" over all animations
  int scale_channels = 0;     // channels with path "scale" (segments of objects whose topology changed)
  int keyframes = 0;          // input count of the first animation's first sampler (0 without animation)
  std::string interpolation;  // that sampler's interpolation ("STEP"), "" without animation
  double duration_s = 0;      // its last input time, seconds
};

// Reads the structure of an animated .glb/.gltf. Throws MeshIoError on a missing or unparseable file.
MorphAnimationInfo read_morph_animation_info(const std::filesystem::path& path);

// Positions (#V, world units, as stored: float32 widened) of the mesh named `mesh_name` at recorded frame index
// `frame` (0 = the base, k ≥ 1 = base + target k−1). Throws MeshIoError when the mesh or the frame does not exist.
std::vector<glm::dvec3> read_morph_frame_positions(const std::filesystem::path& path, const std::string& mesh_name,
                                                   int frame);

}  // namespace trispline::core
