// core::ring_lattice (core/placement/ring_lattice.h): bad sizes are refused (radius within half the width, fewer
// control points than the order, orders outside 2..4).
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/placement/ring_lattice.h"

using namespace trispline;

namespace {

TEST(RingLatticeFunction, RejectsBadSizes) {
  EXPECT_THROW(core::ring_lattice({0, 0, 0}, 0.2, 0.5, 0.1, {16, 2, 2}, {4, 2, 2}), std::invalid_argument);
  EXPECT_THROW(core::ring_lattice({0, 0, 0}, 1.0, 0.5, 0.1, {3, 2, 2}, {4, 2, 2}), std::invalid_argument);
  EXPECT_THROW(core::ring_lattice({0, 0, 0}, 1.0, 0.5, 0.1, {16, 2, 2}, {5, 2, 2}), std::invalid_argument);
  EXPECT_NO_THROW(core::ring_lattice({0, 0, 0}, 1.0, 0.5, 0.1, {16, 2, 2}, {4, 2, 2}));
}

}  // namespace
