// SPDX-License-Identifier: MIT
// writeFileAtomically, which every output of odeskin goes through, on targets that are not plain
// files: a symbolic link, a FIFO (standing in for /dev/null and /dev/stdout, which a test must not
// risk replacing), a directory.
#include "engine/io/obj_io.hpp"
#include "engine/io/text_tokens.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include "scratch_dir.hpp"  // tests/

namespace odeskin {
namespace {

namespace fs = std::filesystem;

fs::path freshDir() { return odeskin::testing::testScratchDir(); }

std::string contents(const fs::path& path) {  // "" for a file that is not there
  Result<std::string> text = readTextFile(path);
  return text.ok() ? std::move(text).value() : std::string();
}

TEST(WriteFileAtomically, ReplacesARegularFile) {
  const fs::path file = freshDir() / "out.txt";
  ASSERT_TRUE(writeFileAtomically(file, "first").ok());
  ASSERT_TRUE(writeFileAtomically(file, "second").ok());
  EXPECT_EQ(contents(file), "second");
  EXPECT_EQ(std::distance(fs::directory_iterator(file.parent_path()), fs::directory_iterator{}), 1);  // no temporary left
}

// The temporary was created with the umask's mode, so replacing a group-writable (or private)
// output changed who may write (or read) it.
TEST(WriteFileAtomically, AReplacedFileKeepsItsPermissions) {
  const fs::path dir = freshDir();
  const fs::path shared = dir / "shared.odsk";
  const fs::path secret = dir / "secret.odsk";
  ASSERT_TRUE(writeFileAtomically(shared, "first").ok());
  ASSERT_TRUE(writeFileAtomically(secret, "first").ok());
  const fs::perms group_writable = fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                                   fs::perms::group_write | fs::perms::others_read;
  const fs::perms owner_only = fs::perms::owner_read | fs::perms::owner_write;
  fs::permissions(shared, group_writable);
  fs::permissions(secret, owner_only);
  ASSERT_TRUE(writeFileAtomically(shared, "second").ok());
  ASSERT_TRUE(writeFileAtomically(secret, "second").ok());
  EXPECT_EQ(contents(shared), "second");
  EXPECT_EQ(fs::status(shared).permissions(), group_writable);
  EXPECT_EQ(fs::status(secret).permissions(), owner_only);
}

// Renaming onto a link replaced the link with a plain file, and the file it named never changed.
TEST(WriteFileAtomically, FollowsASymbolicLink) {
  const fs::path dir = freshDir();
  fs::create_directories(dir / "real");
  fs::create_symlink(dir / "real" / "target.obj", dir / "link.obj");  // dangling until written
  ASSERT_TRUE(writeFileAtomically(dir / "link.obj", "first").ok());
  EXPECT_TRUE(fs::is_symlink(dir / "link.obj"));
  EXPECT_EQ(contents(dir / "real" / "target.obj"), "first");
  ASSERT_TRUE(writeFileAtomically(dir / "link.obj", "second").ok());
  EXPECT_TRUE(fs::is_symlink(dir / "link.obj"));
  EXPECT_EQ(contents(dir / "real" / "target.obj"), "second");
}

// As root, `odeskin fit ... -o /dev/null` renamed the asset over /dev/null and left a regular
// file there. A FIFO shows the same: the node must stay, and the bytes go through it.
TEST(WriteFileAtomically, WritesIntoAFifoInPlace) {
  const fs::path fifo = freshDir() / "out.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // so the writer's open does not block
  ASSERT_GE(reader, 0);
  EXPECT_TRUE(writeFileAtomically(fifo, "through the pipe\n").ok());
  char buffer[64] = {};
  const ssize_t n = ::read(reader, buffer, sizeof buffer);
  ::close(reader);
  EXPECT_EQ(std::string(buffer, static_cast<std::size_t>(n > 0 ? n : 0)), "through the pipe\n");
  EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST(WriteFileAtomically, RefusesADirectory) {
  const fs::path dir = freshDir();
  const Status s = writeFileAtomically(dir, "x");
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_EQ(s.message(), dir.string() + ": is a directory");
  EXPECT_TRUE(fs::is_directory(dir));
}

}  // namespace
}  // namespace odeskin
