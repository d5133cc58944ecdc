// Running command lines straight on a core::Scene (no registry, no history), for the tests of one command.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "core/commands/command.h"
#include "core/scene/scene.h"
#include "tests/error_field.h"

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

// The field a CommandError blames when `line` is parsed as C and redone on `scene`; "(accepted)" when it runs.
template <class C>
std::string command_field_of(core::Scene& scene, const nlohmann::json& line) {
  return field_of<core::CommandError>([&] { C::parse(line, core::CommandContext{})->redo(scene); });
}

// Same objects in the same order, with bit-for-bit equal world meshes (positions).
inline void expect_same_meshes(const core::Scene& a, const core::Scene& b) {
  ASSERT_EQ(a.objects().size(), b.objects().size());
  for (std::size_t i = 0; i < a.objects().size(); ++i) {
    EXPECT_EQ(a.objects()[i].name, b.objects()[i].name);
    EXPECT_EQ(a.objects()[i].world_mesh->positions, b.objects()[i].world_mesh->positions) << a.objects()[i].name;
  }
}

}  // namespace trispline::test
