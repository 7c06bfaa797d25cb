// SPDX-License-Identifier: MIT
// PendingFile / removePendingFiles: what the command line's signal handler removes is exactly the
// temporaries being written at that moment, and a slot is reused only once its mark is gone.

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/pending_files.hpp"
#include "scratch_dir.hpp"  // tests/

namespace odeskin {
namespace {

namespace fs = std::filesystem;

class PendingFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = odeskin::testing::scratchDir("pending_files");
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path touch(const std::string& name) const {
    std::ofstream(dir_ / name) << "partial";
    return dir_ / name;
  }
  fs::path dir_;
};

TEST_F(PendingFiles, OnlyTheFilesStillMarkedAreRemoved) {
  const fs::path written = touch("written.obj.tmp1");
  const fs::path pending = touch("pending.obj.tmp2");
  const fs::path unrelated = touch("pending.obj");
  { const PendingFile done(written); }  // renamed into place and released before the signal
  const PendingFile mark(pending);
  removePendingFiles();
  EXPECT_TRUE(fs::exists(written));
  EXPECT_FALSE(fs::exists(pending));
  EXPECT_TRUE(fs::exists(unrelated));
}

// Registered by absolute path: a host thread may change directory before a signal arrives.
TEST_F(PendingFiles, ARelativePathIsRemovedAfterAChangeOfDirectory) {
  const fs::path before = fs::current_path();
  fs::current_path(dir_);
  touch("relative.obj.tmp3");
  {
    const PendingFile mark("relative.obj.tmp3");
    fs::current_path(before);
    removePendingFiles();
  }
  EXPECT_FALSE(fs::exists(dir_ / "relative.obj.tmp3"));
}

TEST_F(PendingFiles, ASlotIsReusedOnlyAfterItsMarkIsGone) {
  std::vector<std::unique_ptr<PendingFile>> marks;
  marks.reserve(kMaxPendingFiles);
  for (int i = 0; i < kMaxPendingFiles; ++i) {
    marks.push_back(std::make_unique<PendingFile>(touch(std::string("a").append(std::to_string(i)))));
  }
  removePendingFiles();  // every slot now removed but still named by its mark
  const fs::path late = touch("late");
  { const PendingFile unregistered(late); }  // no free slot: not registered, and nothing breaks
  marks.clear();                             // the marks free their slots
  const PendingFile again(late);
  removePendingFiles();
  EXPECT_FALSE(fs::exists(late));
  for (int i = 0; i < kMaxPendingFiles; ++i) {
    EXPECT_FALSE(fs::exists(dir_ / std::string("a").append(std::to_string(i))));
  }
}

TEST_F(PendingFiles, MoreFilesThanSlotsOrTooLongAPathAreWrittenUnregistered) {
  std::vector<std::unique_ptr<PendingFile>> marks;
  marks.reserve(kMaxPendingFiles);
  for (int i = 0; i < kMaxPendingFiles; ++i) {
    marks.push_back(std::make_unique<PendingFile>(touch(std::string("b").append(std::to_string(i)))));
  }
  const fs::path extra = touch("extra");
  const PendingFile over(extra);
  const PendingFile too_long(fs::path(std::string(kMaxPendingPathBytes, 'x')));
  removePendingFiles();
  EXPECT_TRUE(fs::exists(extra));
  EXPECT_FALSE(fs::exists(dir_ / "b0"));
}

}  // namespace
}  // namespace odeskin
