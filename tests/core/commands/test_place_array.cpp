// place.array: copies trailing a placed object along its path, undo, errors.
#include <gtest/gtest.h>

#include "tests/core/commands/placed_crate.h"

namespace trispline::core {
namespace place_array_test {

using nlohmann::json;

TEST(PlaceArray, CopiesTrailAlongThePathAndUndoRemovesThem) {
  Scene s = test::placed_crate(0.25);
  test::run_crate_line(s, json::parse(R"({"cmd":"anim.keyframe","object":"crate","frame":1,"u":0.75})"));
  const Scene before = s;
  auto c = test::run_crate_line(s, json::parse(R"({"cmd":"place.array","object":"crate","count":2,"spacing":0.3})"));
  ASSERT_EQ(s.objects().size(), 4u);
  EXPECT_EQ(s.objects()[2].name, "crate.001");
  EXPECT_EQ(s.objects()[3].name, "crate.002");
  EXPECT_DOUBLE_EQ(s.find("crate.001")->offset_keys[0].offset.x, 0.75 - 0.3);
  EXPECT_DOUBLE_EQ(s.find("crate.002")->offset_keys[0].offset.x, 0.75 - 0.6);
  EXPECT_EQ(s.find("crate.001")->ffd, s.find("crate")->ffd);  // one shared lattice
  const double x0 = test::centroid(*s.find("crate")->world_mesh).x,
               x1 = test::centroid(*s.find("crate.001")->world_mesh).x,
               x2 = test::centroid(*s.find("crate.002")->world_mesh).x;
  EXPECT_GT(x0, x1 + 0.1);  // in a row, the copies behind the leader
  EXPECT_GT(x1, x2 + 0.1);
  c->undo(s);
  test::expect_same_meshes(s, before);
  c->redo(s);  // redo gives the same names and meshes
  EXPECT_EQ(s.objects()[3].name, "crate.002");
  CommandContext ctx;
  EXPECT_THROW(PlaceArrayCommand::parse(json::parse(R"({"cmd":"place.array","object":"crate","count":0})"), ctx),
               CommandError);
  auto undeformed = PlaceArrayCommand::parse(json::parse(R"({"cmd":"place.array","object":"ground","count":2})"), ctx);
  const std::size_t n = s.objects().size();
  EXPECT_THROW(undeformed->redo(s), CommandError);
  EXPECT_EQ(s.objects().size(), n);
}

}  // namespace place_array_test
}  // namespace trispline::core
