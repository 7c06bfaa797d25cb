// SPDX-License-Identifier: MIT
#include "engine/core/finite_vector.hpp"

#include <limits>

#include <gtest/gtest.h>

#include "engine/core/types.hpp"

namespace odeskin {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(FiniteVector, EveryComponentCounts) {
  EXPECT_TRUE(isFinite(Vec3(1.0, -2.0, std::numeric_limits<double>::max())));
  EXPECT_TRUE(isFinite(Vec2(0.0, std::numeric_limits<double>::denorm_min())));
  for (int i = 0; i < 3; ++i) {
    Vec3 p(1.0);
    p[i] = kNaN;
    EXPECT_FALSE(isFinite(p)) << "NaN in component " << i;
    p[i] = -kInf;
    EXPECT_FALSE(isFinite(p)) << "-inf in component " << i;
  }
  EXPECT_FALSE(isFinite(Vec2(0.0, kInf)));
  EXPECT_FALSE(isFinite(glm::vec4(0.0F, 0.0F, 0.0F, std::numeric_limits<float>::quiet_NaN())));
}

}  // namespace
}  // namespace odeskin
