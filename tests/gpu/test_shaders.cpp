#include <algorithm>
#include <filesystem>
#include <set>

#include "gl_test.h"
#include "gpu/gl/shader_program.h"
#include "gpu/gl/shader_sources.h"

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

TEST(ShaderSources, IncludesExpandWithLineDirectives) {
  std::vector<std::string> included;
  const std::string s = expand_includes("#version 430 core\n// a\n#include \"ffd_eval.glsl\"\nvoid main() {}\n",
                                        "x.comp.glsl", &included);
  ASSERT_EQ(included, std::vector<std::string>{"ffd_eval.glsl"});
  EXPECT_EQ(s.rfind("#version 430 core\n// a\n#line 2 1\n", 0), 0u) << s.substr(0, 80);
  EXPECT_NE(s.find("void ffd_eval("), std::string::npos);
  EXPECT_EQ(s.find("#version", 1), std::string::npos) << "the library's #version line is dropped";
  EXPECT_NE(s.find("\n#line 4 0\nvoid main() {}\n"), std::string::npos);
  EXPECT_THROW(expand_includes("#version 430 core\n#include \"nope.glsl\"\n", "x.comp.glsl"), ShaderError);
  EXPECT_THROW(expand_includes("#version 430 core\n#include nope\n", "x.comp.glsl"), ShaderError);
  EXPECT_TRUE(is_shader_stage_file("ffd.comp.glsl"));
  EXPECT_FALSE(is_shader_stage_file("ffd_eval.glsl"));
}

// Every .vert pairs with the .frag of the same base name; every file compiles and every pair links; include
// libraries (no stage suffix) are compiled through the files that include them.
TEST_F(GlTest, EveryEmbeddedShaderCompilesAndLinks) {
  int linked = 0;
  for (std::string_view n : shader_names()) {
    const std::string name(n);
    if (!is_shader_stage_file(name)) continue;
    const GLenum stage = shader_stage_from_name(name);
    if (stage == GL_COMPUTE_SHADER) {
      EXPECT_NO_THROW(ShaderProgram({name})) << name;
      ++linked;
    } else if (stage == GL_VERTEX_SHADER) {
      // Its own fragment shader, else the shared studio shading (ddm.vert.glsl draws with mesh.frag.glsl).
      std::string frag = name.substr(0, name.size() - std::string(".vert.glsl").size()) + ".frag.glsl";
      const auto names = shader_names();
      if (std::find(names.begin(), names.end(), frag) == names.end()) frag = "mesh.frag.glsl";
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
  // The FFD variants: compute with normals, the vertex path drawn and captured by transform feedback.
  EXPECT_NO_THROW(
      ShaderProgram({"ffd.comp.glsl"}, {{"ORDER_U", "2"}, {"ORDER_V", "4"}, {"ORDER_W", "3"}, {"FFD_NORMALS", ""}}));
  EXPECT_NO_THROW(ShaderProgram({"mesh.vert.glsl", "mesh.frag.glsl"},
                                {{"FFD", ""}, {"FFD_NORMALS", ""}, {"OUTLINE", ""}, {"FLAT_COLOR", ""}}));
  EXPECT_NO_THROW(ShaderProgram({"mesh.vert.glsl"}, {{"FFD", ""}}, {"v_world", "v_normal"}));
  // DDM tile instances: outline variant and the transform-feedback capture.
  EXPECT_NO_THROW(ShaderProgram({"ddm.vert.glsl", "mesh.frag.glsl"}, {{"OUTLINE", ""}, {"FLAT_COLOR", ""}}));
  EXPECT_NO_THROW(ShaderProgram({"ddm.vert.glsl"}, {}, {"v_world", "v_normal"}));
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
  // An error inside an included library is reported with the library's name.
  try {
    ShaderProgram p({"ffd.comp.glsl"}, {{"ffd_span", "+"}});  // declared in ffd_eval.glsl only
    FAIL() << "expected a ShaderError";
  } catch (const ShaderError& e) {
    EXPECT_NE(std::string(e.what()).find("source string 1 = gpu/shaders/ffd_eval.glsl"), std::string::npos) << e.what();
  }
}

}  // namespace trispline::gpu::test
