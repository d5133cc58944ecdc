#include <algorithm>
#include <filesystem>
#include <set>

#include "gl_test.h"
#include "gpu/shader_program.h"
#include "gpu/shader_sources.h"

namespace trispline::gpu::test {

TEST(ShaderSources, EveryGlslFileIsEmbedded) {
  std::set<std::string> on_disk, embedded;
  for (const auto& e : std::filesystem::directory_iterator(TRISPLINE_SOURCE_DIR "/gpu/shaders"))
    if (e.path().extension() == ".glsl") on_disk.insert(e.path().filename().string());
  for (std::string_view n : shader_names()) embedded.insert(std::string(n));
  EXPECT_EQ(on_disk, embedded);
  EXPECT_FALSE(embedded.empty());
  for (std::string_view n : shader_names()) EXPECT_EQ(shader_source(n).rfind("#version 430 core", 0), 0u) << n;
  EXPECT_THROW(shader_source("nope.frag.glsl"), std::out_of_range);
}

TEST(ShaderSources, DefinesGoRightAfterVersion) {
  const std::string s =
      specialise_source("#version 430 core\nvoid main() {}\n", {{"ORDER_U", "3"}, {"FLAG", ""}}, "x.comp.glsl");
  EXPECT_EQ(s, "#version 430 core\n#define ORDER_U 3\n#define FLAG\n#line 2\nvoid main() {}\n");
  EXPECT_THROW(specialise_source("void main() {}\n", {}, "x.comp.glsl"), ShaderError);
  EXPECT_EQ(shader_stage_from_name("a.comp.glsl"), GLenum(GL_COMPUTE_SHADER));
  EXPECT_THROW(shader_stage_from_name("a.glsl"), ShaderError);
}

// Every .vert pairs with the .frag of the same base name; every file compiles and every pair links.
TEST_F(GlTest, EveryEmbeddedShaderCompilesAndLinks) {
  int linked = 0;
  for (std::string_view n : shader_names()) {
    const std::string name(n);
    const GLenum stage = shader_stage_from_name(name);
    if (stage == GL_COMPUTE_SHADER) {
      EXPECT_NO_THROW(ShaderProgram({name})) << name;
      ++linked;
    } else if (stage == GL_VERTEX_SHADER) {
      const std::string frag = name.substr(0, name.size() - std::string(".vert.glsl").size()) + ".frag.glsl";
      EXPECT_NO_THROW(ShaderProgram({name, frag})) << name;
      ++linked;
    }
  }
  EXPECT_GE(linked, 4);
  // The variants the renderer uses (and the renderer itself, which builds all of them).
  EXPECT_NO_THROW(ShaderProgram({"mesh.vert.glsl", "mesh.frag.glsl"}, {{"OUTLINE", ""}, {"FLAT_COLOR", ""}}));
  EXPECT_NO_THROW(ShaderProgram({"lines.vert.glsl", "lines.frag.glsl"}, {{"SCREEN_SPACE", ""}}));
  EXPECT_NO_THROW(ShaderProgram({"lines.vert.glsl", "lines.frag.glsl"}, {{"ROUND_POINTS", ""}}));
  EXPECT_NO_THROW(ShaderProgram({"lines.vert.glsl", "lines.frag.glsl"}, {{"DEPTH_PULL", ""}}));
  EXPECT_NO_THROW(ShaderProgram({"mesh.vert.glsl", "mesh.frag.glsl"}, {{"DEPTH_PULL", ""}, {"TRANSLUCENT", ""}}));
  EXPECT_NO_THROW(Renderer());
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GlTest, CompileErrorNamesFileAndCarriesInfoLog) {
  try {
    // A define that turns a declaration into garbage: the compile must fail and say where.
    ShaderProgram p({"mesh.vert.glsl", "mesh.frag.glsl"}, {{"u_view_proj", "+"}});
    FAIL() << "expected a ShaderError";
  } catch (const ShaderError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gpu/shaders/mesh.vert.glsl"), std::string::npos) << what;
    EXPECT_NE(what.find("u_view_proj=+"), std::string::npos) << what;
    ASSERT_NE(what.find(":\n"), std::string::npos) << what;
    EXPECT_GT(what.size(), what.find(":\n") + 5) << "no info log in: " << what;
  }
}

}  // namespace trispline::gpu::test
