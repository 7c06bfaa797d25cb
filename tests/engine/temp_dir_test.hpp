// SPDX-License-Identifier: MIT
// Fixture base for tests that write synthetic files: a fresh folder per test, removed afterwards.
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "scratch_dir.hpp"  // tests/

namespace odeskin::testing {

class TempDirTest : public ::testing::Test {
 protected:
  // `prefix` names the test file's folders.
  explicit TempDirTest(std::string prefix) : prefix_(std::move(prefix)) {}

  void SetUp() override {
    dir_ = testScratchDir(prefix_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path write(const std::string& name, const std::string& text) const {
    std::filesystem::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  // The bytes of `name` in the folder (empty when it cannot be read).
  std::string read(const std::string& name) const {
    std::ifstream in(dir_ / name, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace odeskin::testing
