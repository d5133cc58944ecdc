// `object.inside` — what an object's cut surfaces look like: the colour of its kMaterialInside faces (DFFD caps,
// incision walls) and the texture its DFFD caps carry (seed §6.5, Fig. 6.9: a tree split open with wood-textured
// caps). Fields: declared in object_inside.cpp (ParamSchema), listed in docs/commands.md.
// The texture (PNG, JPEG, EXR, TIFF, BMP, TGA through OpenImageIO; at most kMaxModelTextureFileBytes and
// kMaxMaterialImageBytes decoded) is read and decoded before the scene is touched; a file that cannot be read or
// decoded fails the command (CommandError "texture", the reader's message), the object unchanged. The object's DFFD
// caps are then rebuilt with vertices of their own (planar uvs in the discontinuity plane, one repeat per
// `texture_size` world units) and drawn textured in Material shading; exports write the texture into the
// "<name>.inside" material. Undo restores colour, texture and mesh.
// Errors beyond the declared ranges: unknown object ("object"); nothing to change ("color").
#pragma once

#include <optional>
#include <string>

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"

namespace trispline::core {

struct ObjectInsideParams {
  std::string object;
  std::optional<glm::vec3> color;      // linear RGB; unset = unchanged
  std::string texture;                 // image file, absolute once parsed; "" = unchanged
  bool no_texture = false;             // remove the texture (not with `texture`)
  std::optional<double> texture_size;  // world units per repeat; unset = unchanged
};

struct ObjectInsideCommand : ObjectSnapshotCommand<ObjectInsideCommand, ObjectInsideParams> {
  static Schema declare();
  std::optional<SceneObject> build(const Scene& scene) override;
};

// Reads and decodes an inside texture (object.inside "texture"). Throws CommandError (field "texture"): the file
// cannot be read (check_input_file's messages, over kMaxModelTextureFileBytes) or decoded (decode_material_image's).
std::shared_ptr<const MaterialImage> read_inside_texture(const std::string& path);

}  // namespace trispline::core
