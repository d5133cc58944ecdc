// farm.json's reader (editor/farm/farm_plan.h) on the fuzz target's seeds: the valid plans of both kinds read back to
// the same text, and every hostile one is refused with FarmPlanError naming the key at fault.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "editor/farm/farm_plan.h"

namespace trispline::editor {
namespace {

const std::filesystem::path kSeeds = std::filesystem::path(TRISPLINE_SOURCE_DIR) / "tests/fuzz/corpus/fuzz_farm_json";

std::string read_seed(const std::string& name) {
  std::ifstream in(kSeeds / name, std::ios::binary);
  EXPECT_TRUE(in) << name;
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(FarmPlan, ValidPlansReadBackToTheSameText) {
  for (const char* name : {"frames_valid.json", "batch_valid.json"}) {
    const FarmPlan plan = parse_farm_plan(read_seed(name), "/somewhere/farm");
    EXPECT_EQ(plan.dir, "/somewhere/farm");  // where it was read, never a path stored in it
    const std::string text = plan.to_json().dump(2);
    EXPECT_EQ(parse_farm_plan(text, "/x").to_json().dump(2), text) << name;
  }
  const FarmPlan frames = parse_farm_plan(read_seed("frames_valid.json"), "/f");
  ASSERT_EQ(frames.tasks.size(), 4u);
  EXPECT_EQ(frames.tasks[3].first, 13);
  EXPECT_EQ(frames.tasks[3].last, 16);
  EXPECT_FALSE(frames.to_json().contains("dir"));
}

TEST(FarmPlan, HostilePlansAreRefusedNamingTheKey) {
  const std::vector<std::pair<const char*, const char*>> cases = {
      {"chunk_zero.json", "chunk"},
      {"huge_last.json", "tasks[3].last"},
      {"dropped_task.json", "tasks"},
      {"frame_last_huge.json", "frame_last"},
      {"partition_newline.json", "partition"},
      {"batch_name_escape.json", "tasks[1].name"},
      {"log_relative.json", "log"},
      {"fps_inf.json", ""},  // 1e999 is not a JSON number nlohmann reads
      {"fps_out_of_range.json", "fps"},
      {"chunk_float.json", "chunk"},
      {"chunk_u64.json", "chunk"},
      {"task_pids_bad.json", "jobs[0].task_pids[1]"},
      {"old_version.json", "version"},
      {"not_object.json", ""},
      {"truncated.json", ""},
  };
  for (const auto& [name, key] : cases) {
    try {
      parse_farm_plan(read_seed(name), "/f");
      ADD_FAILURE() << name << " was accepted";
    } catch (const FarmPlanError& e) {
      EXPECT_EQ(e.key(), key) << name << ": " << e.what();
      if (*key) {
        EXPECT_NE(std::string(e.what()).find(std::string("'") + key + "'"), std::string::npos) << e.what();
      }
    }
  }
}

TEST(FarmPlan, TasksMustBeTheFramesCutIntoChunks) {
  nlohmann::json j = nlohmann::json::parse(read_seed("frames_valid.json"));
  j["tasks"][1]["first"] = 6;  // a gap between tasks 0 and 1
  EXPECT_THROW(parse_farm_plan(j.dump(), "/f"), FarmPlanError);
  j = nlohmann::json::parse(read_seed("frames_valid.json"));
  j["chunk"] = 5;  // 16 frames in chunks of 5 are 4 tasks of other ranges
  EXPECT_THROW(parse_farm_plan(j.dump(), "/f"), FarmPlanError);
  j = nlohmann::json::parse(read_seed("frames_valid.json"));
  j["jobs"][0]["tasks"] = {0, 4};  // no task 4
  EXPECT_THROW(parse_farm_plan(j.dump(), "/f"), FarmPlanError);
  j = nlohmann::json::parse(read_seed("batch_valid.json"));
  j["tasks"][2]["name"] = j["tasks"][0]["name"];  // two runs into one folder
  EXPECT_THROW(parse_farm_plan(j.dump(), "/f"), FarmPlanError);
  j["tasks"][2]["name"] = "..";
  EXPECT_THROW(parse_farm_plan(j.dump(), "/f"), FarmPlanError);
}

TEST(FarmPlan, SbatchValuesCannotEndTheirLine) {
  EXPECT_EQ(check_sbatch_value("--partition", "render,gpu-a100"), "");
  EXPECT_EQ(check_sbatch_value("--time", "1-00:30:00"), "");
  for (const char* bad : {"render\ntouch /tmp/x", "render\r", "a b", "a'b", "a\x7f"}) {
    const std::string why = check_sbatch_value("--partition", bad);
    EXPECT_NE(why.find("--partition"), std::string::npos) << bad;
  }
  EXPECT_NE(check_sbatch_value("--time", "00:10:00\n#SBATCH --x"), "");
}

TEST(FarmPlan, PlanFramesRefusesEmptyOrUnboundedRanges) {
  EXPECT_EQ(plan_frames(1, 16, 4).size(), 4u);
  EXPECT_EQ(plan_frames(5, 5, 100).size(), 1u);
  EXPECT_THROW(plan_frames(1, 16, 0), std::invalid_argument);
  EXPECT_THROW(plan_frames(9, 3, 2), std::invalid_argument);
  EXPECT_THROW(plan_frames(0, 2147483647, 1), std::invalid_argument);
}

}  // namespace
}  // namespace trispline::editor
