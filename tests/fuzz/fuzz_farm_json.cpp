// libFuzzer target: farm.json's reader and checks (editor/farm/farm_plan.h), what `trispline farm status|resume|
// assemble|task` run on a farm folder someone else wrote. Any input must either give a plan or throw FarmPlanError
// naming a key; any other exception, a crash or a hang is a finding. A plan that is accepted must write itself as
// farm.json text that reads back to the same text (what the farm writes, it must read), and its tasks must be the
// bounded, consistent set the farm's status and assembly loop over.
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "editor/farm/farm_plan.h"

using namespace trispline;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  editor::FarmPlan plan;
  try {
    plan = editor::parse_farm_plan(text, "/farm");
  } catch (const editor::FarmPlanError&) {
    return 0;
  }
  if (plan.tasks.empty() || plan.tasks.size() > static_cast<std::size_t>(editor::kFarmMaxFrame + 1)) std::abort();
  if (plan.kind == "frames") {
    if (plan.chunk < 1 || plan.tasks.front().first != plan.frame_first || plan.tasks.back().last != plan.frame_last)
      std::abort();
  }
  const std::string written = plan.to_json().dump(2);
  const editor::FarmPlan again = editor::parse_farm_plan(written, "/farm");  // must not throw
  if (again.to_json().dump(2) != written) std::abort();
  return 0;
}
