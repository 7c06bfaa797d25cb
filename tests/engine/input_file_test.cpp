// SPDX-License-Identifier: MIT
// readInputFile: regular files and pipes are read, directories and devices refused before any read
// (a .obj linked to /dev/zero was read until memory ran out), and a pipe stops at its bound.
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>

#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "engine/core/input_file.hpp"
#include "scratch_dir.hpp"  // tests/

namespace odeskin {
namespace {

namespace fs = std::filesystem;

class InputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = odeskin::testing::scratchDir("input_file");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

void expectIoError(const Result<std::string>& r, const fs::path& path, const std::string& problem) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kIoError);
  EXPECT_EQ(r.status().message(), path.string() + ": " + problem);
}

TEST_F(InputFile, ReadsARegularFileWhole) {
  std::string bytes(200'000, 'x');
  bytes[7] = '\0';
  bytes.back() = '\n';
  std::ofstream(dir_ / "a.bin", std::ios::binary) << bytes;
  const Result<std::string> r = readInputFile(dir_ / "a.bin");
  ASSERT_TRUE(r.ok()) << r.status().toString();
  EXPECT_EQ(*r, bytes);
  { const std::ofstream empty(dir_ / "empty.obj"); }  // created, and closed at once
  EXPECT_EQ(readInputFile(dir_ / "empty.obj").value(), "");
}

TEST_F(InputFile, RefusesMissingFilesDirectoriesAndDevices) {
  expectIoError(readInputFile(dir_ / "absent.obj"), dir_ / "absent.obj", "cannot open for reading");
  fs::create_directories(dir_ / "folder.obj");
  expectIoError(readInputFile(dir_ / "folder.obj"), dir_ / "folder.obj", "is a directory, not a file");
  // Through a link with an input's name, as a user's file could be; /dev/zero never ends.
  fs::create_symlink("/dev/zero", dir_ / "zero.obj");
  expectIoError(readInputFile(dir_ / "zero.obj"), dir_ / "zero.obj", "is a device, not a file");
  expectIoError(readInputFile("/dev/null"), "/dev/null", "is a device, not a file");
}

// A pipe (process substitution, /dev/stdin) is read to its end, and past its bound it is an error,
// not the end of memory.
TEST_F(InputFile, ReadsAPipeUpToItsBound) {
  const fs::path fifo = dir_ / "pipe.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << text; });
  const Result<std::string> r = readInputFile(fifo);
  writer.join();
  ASSERT_TRUE(r.ok()) << r.status().toString();
  EXPECT_EQ(*r, text);

  // The reader stops early and closes the pipe; the writer's next write then fails with EPIPE
  // instead of raising SIGPIPE.
  struct sigaction ignore = {};
  struct sigaction old = {};
  ignore.sa_handler = SIG_IGN;
  ASSERT_EQ(::sigaction(SIGPIPE, &ignore, &old), 0);
  const std::string big(3 * 65536 + 11, 'v');
  std::thread flood([&] { std::ofstream(fifo, std::ios::binary) << big; });
  const Result<std::string> bounded = readInputFile(fifo, 65536);
  flood.join();
  ::sigaction(SIGPIPE, &old, nullptr);
  expectIoError(bounded, fifo, "more than 65536 bytes from a pipe");
}

}  // namespace
}  // namespace odeskin
