// anim.record (core/commands/anim_record.h) through the registry and the history, as a log replays it: a request
// resolves the whole timeline when it names no frames, changes nothing and is never an undo step; a range outside
// the timeline, an unknown format or a half-given size names its field. Recording itself: tests/editor/test_record.cpp.
#include <gtest/gtest.h>

#include "core/commands/anim_record.h"
#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "tests/core/commands/command_test_util.h"
#include "tests/core/commands/history_test_util.h"

using namespace trispline;

namespace anim_record_test {

using nlohmann::json;

// A ground plane and a teapot on a timeline of frames 1-12.
core::Scene twelve_frames() {
  core::Scene s;
  editor::History history(s);
  for (const char* line : {R"({"cmd":"anim.timeline","fps":24,"start":1,"end":12})",
                           R"({"cmd":"scene.primitive","kind":"plane","name":"ground","scale":[3,1,3]})",
                           R"({"cmd":"scene.primitive","kind":"teapot","name":"t1","scale":0.3})"})
    test::run(history, json::parse(line));
  return s;
}

TEST(AnimRecord, BadRequestsNameTheirFieldAndAGoodOneChangesNothing) {
  const core::Scene scene = twelve_frames();
  // A range outside the timeline names "frames", an unknown format "format"; the scene is untouched.
  core::Scene s = scene;
  editor::History history(s);
  const core::CommandContext ctx;
  const auto& registry = editor::CommandRegistry::builtin();
  try {
    history.execute(registry.parse({{"cmd", "anim.record"}, {"frames", {10, 20}}}, ctx));
    ADD_FAILURE() << "frames outside the timeline accepted";
  } catch (const core::CommandError& e) {
    EXPECT_EQ(e.field(), "frames");
    EXPECT_NE(std::string(e.what()).find("outside the timeline 1-12"), std::string::npos) << e.what();
  }
  EXPECT_EQ(history.size(), 0u);
  try {
    registry.parse({{"cmd", "anim.record"}, {"format", "gif"}}, ctx);
    ADD_FAILURE() << "format gif accepted";
  } catch (const core::CommandError& e) {
    EXPECT_EQ(e.field(), "format");
  }
  // A good request resolves the whole timeline, changes nothing, and undoes to nothing.
  history.execute(registry.parse({{"cmd", "anim.record"}, {"out", "x"}}, ctx));
  EXPECT_EQ(history.size(), 0u) << "anim.record is never an undo step";
  const auto& cmd = dynamic_cast<const core::AnimRecordCommand&>(history.last_executed());
  EXPECT_EQ(cmd.request().frame_first, 1);
  EXPECT_EQ(cmd.request().frame_last, 12);
  EXPECT_EQ(cmd.to_json().count("frames"), 0u);
  history.undo();
  EXPECT_EQ(s.objects().size(), scene.objects().size());
  test::expect_same_meshes(s, scene);
  EXPECT_EQ(s.timeline, scene.timeline);
}

TEST(AnimRecord, LineRoundTripsAndResolvesItsFolderAgainstTheLog) {
  core::Scene s = twelve_frames();
  const json line = json::parse(
      R"({"cmd":"anim.record","out":"frames","format":"exr","frames":[3,5],"glb":false,"mp4":false,
          "width":320,"height":240})");
  auto c = core::AnimRecordCommand::parse(line, core::CommandContext{"/tmp/logs", {}});
  EXPECT_EQ(c->to_json(), line);
  EXPECT_EQ(core::AnimRecordCommand::parse(c->to_json(), {})->to_json(), line);
  c->redo(s);
  const auto& r = dynamic_cast<const core::AnimRecordCommand&>(*c).request();
  EXPECT_EQ(r.out_dir, std::filesystem::path("/tmp/logs/frames"));
  EXPECT_EQ(r.format, "exr");
  EXPECT_EQ(r.frame_first, 3);
  EXPECT_EQ(r.frame_last, 5);
  EXPECT_TRUE(r.frames_given);
  EXPECT_FALSE(r.glb);
  EXPECT_FALSE(r.mp4);
  EXPECT_EQ(r.width, 320);
  EXPECT_EQ(r.height, 240);
  EXPECT_EQ(c->stats().at("frames"), 3);
  EXPECT_FALSE(c->undoable());
}

TEST(AnimRecord, FieldErrorsNameTheField) {
  core::Scene s = twelve_frames();
  const core::Scene before = s;
  const auto field_of = [&](const char* line) {
    return test::command_field_of<core::AnimRecordCommand>(s, json::parse(line));
  };
  EXPECT_EQ(field_of(R"({"cmd":"anim.record","frames":[5,4]})"), "frames");
  EXPECT_EQ(field_of(R"({"cmd":"anim.record","frames":[0,3]})"), "frames");  // before the first frame
  EXPECT_EQ(field_of(R"({"cmd":"anim.record","frames":[12,13]})"), "frames");
  EXPECT_EQ(field_of(R"({"cmd":"anim.record","format":"tiff"})"), "format");
  EXPECT_EQ(field_of(R"({"cmd":"anim.record","width":100})"), "height");
  EXPECT_EQ(field_of(R"({"cmd":"anim.record","height":100})"), "width");
  EXPECT_EQ(field_of(R"({"cmd":"anim.record","width":0,"height":100})"), "width");
  EXPECT_EQ(field_of(R"({"cmd":"anim.record","width":16384,"height":16384})"), "width");  // over 8192²
  EXPECT_EQ(field_of(R"({"cmd":"anim.record","glb":"yes"})"), "glb");
  EXPECT_EQ(field_of(R"({"cmd":"anim.record","frames":[1,12]})"), "(accepted)");
  EXPECT_TRUE(test::throws_command_error(
      [&] { core::AnimRecordCommand::parse(json::parse(R"({"cmd":"anim.record","frames":[1,20]})"), {})->redo(s); },
      "frames", "frames 1-20 lie outside the timeline 1-12"));
  test::expect_same_meshes(s, before);
}

}  // namespace anim_record_test
