// What a thrown error says: the field it blames (tests that check each bad input names its own field) or its message.
#pragma once

#include <string>

namespace trispline::test {

// The field() of the `E` that `run()` throws, or "(accepted)" when it throws nothing. E: an exception with field()
// (core::CommandError, core::PlacementError, ...).
template <class E, class F>
std::string field_of(F&& run) {
  try {
    run();
  } catch (const E& e) {
    return e.field();
  }
  return "(accepted)";
}

// The what() of the `E` that `run()` throws, or `none` when it throws nothing.
template <class E, class F>
std::string message_of(F&& run, const std::string& none = "") {
  try {
    run();
  } catch (const E& e) {
    return e.what();
  }
  return none;
}

}  // namespace trispline::test
