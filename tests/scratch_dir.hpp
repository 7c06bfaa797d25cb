// SPDX-License-Identifier: MIT
// Scratch folders for tests that write files. Every folder lives under one root per test process,
// "odeskin_test_<pid>" in the system's temporary folder, which is removed when the process exits:
// ctest runs each test as its own process, and a CI build, a sanitized build and a developer's
// build may run at once on one /tmp, so fixed names collide and names without cleanup pile up.
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

#include <unistd.h>

#include <gtest/gtest.h>

namespace odeskin::testing {

inline const std::filesystem::path& processScratchRoot() {
  struct Root {
    pid_t owner = ::getpid();
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("odeskin_test_" + std::to_string(owner));
    // A forked child that exits normally must not remove its parent's folder.
    ~Root() {
      std::error_code ignored;
      if (::getpid() == owner) std::filesystem::remove_all(path, ignored);
    }
  };
  static Root root;
  return root.path;
}

// An empty folder `name` under the process's root (emptied if an earlier test left it).
inline std::filesystem::path scratchDir(const std::string& name) {
  std::filesystem::path dir = processScratchRoot() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// An empty folder named for the running test, after `prefix`.
inline std::filesystem::path testScratchDir(const std::string& prefix = "") {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return scratchDir(prefix + info->test_suite_name() + "." + info->name());
}

}  // namespace odeskin::testing
