// Running command lines straight on a core::Scene (no registry, no history), for the tests of one command.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "core/commands/command.h"
#include "core/scene/scene.h"

namespace trispline::test {

// Parses `line` with the one of Cs whose id is its "cmd" (the last of Cs when none is), redoes it on `scene` and
// returns it for an undo.
template <class... Cs>
core::CommandPtr run_line(core::Scene& scene, const nlohmann::json& line) {
  const core::CommandContext ctx;
  const std::string id = line.at("cmd");
  core::CommandPtr c;
  ((c == nullptr && id == Cs::schema().id() ? (c = Cs::parse(line, ctx), true) : false), ...);
  if (c == nullptr) c = std::tuple_element_t<sizeof...(Cs) - 1, std::tuple<Cs...>>::parse(line, ctx);
  c->redo(scene);
  return c;
}

// Success when `run()` throws a core::CommandError that blames `field` and whose message contains `words`; else a
// failure saying what happened instead.
template <class F>
::testing::AssertionResult throws_command_error(F&& run, const std::string& field, const std::string& words) {
  try {
    run();
  } catch (const core::CommandError& e) {
    if (e.field() != field) return ::testing::AssertionFailure() << "blames '" << e.field() << "': " << e.what();
    if (std::string(e.what()).find(words) == std::string::npos)
      return ::testing::AssertionFailure() << "no \"" << words << "\" in: " << e.what();
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "no CommandError";
}

}  // namespace trispline::test
