// SPDX-License-Identifier: MIT
#include "samples/decimal_integers.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

// The program's own wiring: options added first, then requireDecimalIntegers, then parse.
struct Program {
  CLI::App app{"test"};
  int count = 0;
  std::uint32_t size = 0;
  std::vector<int> keys;
  double seconds = 0.0;
  std::string name;

  Program() {
    CLI::App* sub = app.add_subcommand("sub");
    sub->add_option("--count", count)->check(CLI::Range(1, 64));
    sub->add_option("--size", size);
    sub->add_option("--keys", keys)->delimiter(',');
    sub->add_option("--seconds", seconds);
    sub->add_option("--name", name);
    odeskin::requireDecimalIntegers(app);
  }
  // The parse error's text, or "" when the arguments parse.
  std::string parse(std::vector<std::string> args) {
    args.insert(args.begin(), "sub");
    std::reverse(args.begin(), args.end());  // CLI11 takes a vector in reverse order
    try {
      app.parse(args);
    } catch (const CLI::ParseError& e) {
      return e.what();
    }
    return "";
  }
};

TEST(DecimalIntegers, LeadingZerosAreDecimalNotOctal) {
  Program p;
  EXPECT_EQ(p.parse({"--count", "010", "--size", "0009", "--keys", "0,007,+012"}), "");
  EXPECT_EQ(p.count, 10);
  EXPECT_EQ(p.size, 9u);
  EXPECT_EQ(p.keys, (std::vector<int>{0, 7, 12}));
  Program q;
  EXPECT_EQ(q.parse({"--count", "-0000", "--size", "0"}), "--count: Value -0 not in range 1 to 64");
}

TEST(DecimalIntegers, OtherBasesAndNonNumbersAreRefusedBeforeTheRange) {
  for (const char* bad : {"0x10", "0X10", "0b1", "0o7", "1e1", "", "+", "-", "1.0", " 1", "1 ", "0x"}) {
    Program p;
    EXPECT_EQ(p.parse({"--count", bad}), "--count: Value " + std::string(bad) + " is not a decimal integer") << bad;
  }
  Program p;
  EXPECT_EQ(p.parse({"--keys", "1,0x2"}), "--keys: Value 0x2 is not a decimal integer");
}

TEST(DecimalIntegers, OtherOptionsAreLeftAlone) {
  Program p;
  EXPECT_EQ(p.parse({"--seconds", "0x1p3", "--name", "0x10"}), "");
  EXPECT_EQ(p.seconds, 8.0);
  EXPECT_EQ(p.name, "0x10");
}

}  // namespace
