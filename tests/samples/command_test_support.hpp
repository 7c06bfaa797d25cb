// SPDX-License-Identifier: MIT
// Calling odeskin's verbs as the program calls them: scratch folders, captured streams, and the
// check that rejected options or inputs end with the right exit code and one error line.
#pragma once

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "samples/odeskin/console.hpp"
#include "scratch_dir.hpp"  // tests/

namespace odeskin::testing {

// An empty folder `prefix` + `name` in the test process's scratch root (scratch_dir.hpp).
inline std::filesystem::path scratchDir(const std::string& prefix, const std::string& name) {
  return scratchDir(prefix + name);
}

// A command's streams, for calling a verb with a Console.
struct Captured {
  std::ostringstream out;
  std::ostringstream err;
  Console console{out, err, false, false};
};

template <typename Options>
struct CommandCase {
  Options options;
  std::string message;  // a part of the expected error line
};

// Every case must exit with `exit_code` and print exactly one line "odeskin: error: VERB: ..."
// that contains its message.
template <typename Options, typename Run>
void expectRejected(const std::vector<CommandCase<Options>>& cases, const Run& run, int exit_code,
                    const std::string& verb) {
  for (const CommandCase<Options>& c : cases) {
    Captured io;
    EXPECT_EQ(run(c.options, io), exit_code) << c.message;
    const std::string err = io.err.str();
    EXPECT_EQ(err.rfind("odeskin: error: " + verb + ": ", 0), 0u) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find(c.message), std::string::npos) << err;
  }
}

}  // namespace odeskin::testing
