// SPDX-License-Identifier: MIT
#include "engine/core/result.hpp"

#include <gtest/gtest.h>

namespace odeskin {
namespace {

Result<int> half(int x) {
  if (x % 2 != 0) return invalidArgument("x=" + std::to_string(x) + " is odd");
  return x / 2;
}

Status quarter(int x, int* out) {
  ODESKIN_ASSIGN_OR_RETURN(int h, half(x));
  ODESKIN_ASSIGN_OR_RETURN(int q, half(h));
  *out = q;
  return okStatus();
}

TEST(Status, DefaultIsOk) {
  Status s;
  EXPECT_TRUE(s.ok());
  EXPECT_EQ(s.toString(), "ok");
}

TEST(Status, ErrorCarriesCodeAndMessage) {
  Status s = illPosed("mode 3: resonant");
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.code(), StatusCode::kIllPosed);
  EXPECT_EQ(s.toString(), "ill-posed: mode 3: resonant");
}

TEST(Result, PropagatesTheFirstError) {
  int out = -1;
  EXPECT_TRUE(quarter(8, &out).ok());
  EXPECT_EQ(out, 2);
  Status s = quarter(6, &out);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "x=3 is odd");
}

}  // namespace
}  // namespace odeskin
