#include "core/commands/object_inside.h"

#include <utility>
#include <vector>

#include "core/mesh/file_check.h"
#include "core/mesh/material_image.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/model_load.h"

namespace trispline::core {

std::shared_ptr<const MaterialImage> read_inside_texture(const std::string& path) {
  std::vector<unsigned char> bytes;
  try {
    bytes = read_input_file(path, kMaxModelTextureFileBytes, "texture files");
  } catch (const MeshIoError& e) {
    throw CommandError(std::string("field 'texture': ") + e.what(), "texture");
  }
  const std::string name = std::filesystem::path(path).filename().string();
  MaterialImage image = decode_material_image(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), "", name, path);
  if (!image.readable()) throw CommandError("field 'texture': '" + path + "': " + image.error, "texture");
  return std::make_shared<const MaterialImage>(std::move(image));
}

auto ObjectInsideCommand::declare() -> Schema {
  return Schema("object.inside", "Set the colour and texture of an object's cut surfaces (DFFD caps, incision walls)")
      .field("object", &P::object, {.required = true, .help = "Object id"})
      .field("color", &P::color,
             {.range = ParamRange{0, 1},
              .unit = "linear RGB",
              .default_text = "unchanged",
              .help = "Colour of the cut surfaces; with a texture, the texture is multiplied by it"})
      .field("texture", &P::texture,
             {.write = ParamWrite::UnlessDefault,
              .path = true,
              .default_text = "unchanged",
              .help = "Image on the DFFD caps (PNG, JPEG, EXR, TIFF, BMP, TGA), relative to the log's folder; "
                      "shown in Material shading and exported; incision walls keep the colour"})
      .field("no_texture", &P::no_texture,
             {.write = ParamWrite::UnlessDefault, .help = "Remove the texture: the colour alone again"})
      .field("texture_size", &P::texture_size,
             {.range = ParamRange{0, 1e6, true, false},
              .unit = "world units",
              .default_text = "unchanged (0.25)",
              .help = "World size of one repeat of the texture on the caps"})
      .check([](P& p) {
        if (!p.texture.empty() && p.no_texture)
          throw CommandError("field 'no_texture': give 'texture' or 'no_texture', not both", "no_texture");
        if (!p.color && p.texture.empty() && !p.no_texture && !p.texture_size)
          throw CommandError("field 'color': give 'color', 'texture', 'no_texture' or 'texture_size'", "color");
      })
      .label([](const P& p) { return "Inside of '" + p.object + "'"; })
      .failure_field("texture");
}

std::optional<SceneObject> ObjectInsideCommand::build(const Scene& scene) {
  SceneObject out = require_object(scene, p_.object);
  if (p_.color) out.inside_color = *p_.color;
  if (!p_.texture.empty()) out.inside_texture = read_inside_texture(p_.texture);
  if (p_.no_texture) out.inside_texture.reset();
  if (p_.texture_size) out.inside_texture_size = *p_.texture_size;
  if (out.dffd) out.refresh();  // the caps with (or without) vertices of their own for the texture
  stats_ = {{"textured", out.inside_textured()}, {"vertices", out.world_mesh ? out.world_mesh->vertex_count() : 0}};
  return out;
}

}  // namespace trispline::core
