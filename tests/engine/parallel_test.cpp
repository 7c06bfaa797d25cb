// SPDX-License-Identifier: MIT
// The TBB wrappers of engine/core/parallel.hpp give TBB's results, in the plain build and under
// ThreadSanitizer (where they also annotate fork and join; scripts/tsan.sh runs this test there, so
// a write in a chunk read by the caller after the join must not be reported).
#include "engine/core/parallel.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/task_arena.h>

namespace odeskin {
namespace {

TEST(Parallel, ForOverRangeWritesEveryElementOnce) {
  constexpr std::size_t kCount = 10007;  // not a multiple of the grain
  std::vector<std::uint64_t> out(kCount, 0);
  std::vector<int> visits(kCount, 0);
  parallelFor(tbb::blocked_range<std::size_t>(0, kCount, 64), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      out[i] = static_cast<std::uint64_t>(i) * i;
      ++visits[i];
    }
  });
  for (std::size_t i = 0; i < kCount; ++i) {
    ASSERT_EQ(out[i], static_cast<std::uint64_t>(i) * i) << "element " << i;
    ASSERT_EQ(visits[i], 1) << "element " << i;
  }
}

TEST(Parallel, ForOverIndicesCoversTheHalfOpenInterval) {
  std::vector<std::uint32_t> out(3000, 0);
  parallelFor(std::uint32_t{5}, std::uint32_t{2900}, [&](std::uint32_t i) { out[i] = i + 1; });
  for (std::uint32_t i = 0; i < out.size(); ++i) {
    ASSERT_EQ(out[i], i >= 5 && i < 2900 ? i + 1 : 0u) << "index " << i;
  }
  // An empty interval runs nothing.
  parallelFor(std::size_t{7}, std::size_t{7}, [&](std::size_t) { out[0] = 99; });
  EXPECT_EQ(out[0], 0u);
}

TEST(Parallel, NestedLoopsWriteTheirOwnRows) {
  constexpr std::size_t kRows = 37;
  constexpr std::size_t kCols = 511;
  std::vector<double> grid(kRows * kCols, 0.0);
  parallelFor(std::size_t{0}, kRows, [&](std::size_t row) {
    parallelFor(tbb::blocked_range<std::size_t>(0, kCols, 16), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t c = r.begin(); c < r.end(); ++c) grid[row * kCols + c] = static_cast<double>(row * 1000 + c);
    });
  });
  for (std::size_t row = 0; row < kRows; ++row) {
    for (std::size_t c = 0; c < kCols; ++c) {
      ASSERT_EQ(grid[row * kCols + c], static_cast<double>(row * 1000 + c)) << row << ", " << c;
    }
  }
}

TEST(Parallel, ReduceGivesTheSerialResult) {
  std::vector<double> values(20011);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<double>((i * 7919) % 10007);
  const double serial_max = *std::max_element(values.begin(), values.end());
  const double parallel_max = parallelReduce(
      tbb::blocked_range<std::size_t>(0, values.size(), 128), -1.0,
      [&](const tbb::blocked_range<std::size_t>& r, double worst) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) worst = std::max(worst, values[i]);
        return worst;
      },
      [](double x, double y) { return std::max(x, y); });
  EXPECT_EQ(parallel_max, serial_max);

  // Integer sums are exact in any order, so the split does not matter.
  const std::uint64_t sum = parallelReduce(
      tbb::blocked_range<std::uint64_t>(1, 100001, 100), std::uint64_t{0},
      [](const tbb::blocked_range<std::uint64_t>& r, std::uint64_t s) {
        for (std::uint64_t i = r.begin(); i < r.end(); ++i) s += i;
        return s;
      },
      [](std::uint64_t x, std::uint64_t y) { return x + y; });
  EXPECT_EQ(sum, std::uint64_t{100000} * 100001 / 2);

  // An empty range gives the identity.
  const int none = parallelReduce(
      tbb::blocked_range<int>(0, 0), 42, [](const tbb::blocked_range<int>&, int v) { return v + 1; },
      [](int x, int y) { return x + y; });
  EXPECT_EQ(none, 42);
}

TEST(Parallel, InvokeRunsEveryFunction) {
  std::vector<int> a;
  std::vector<int> b;
  std::vector<int> c;
  parallelInvoke([&] { a.assign(1000, 1); }, [&] { b.assign(2000, 2); }, [&] { c.assign(3000, 3); });
  EXPECT_EQ(std::accumulate(a.begin(), a.end(), 0), 1000);
  EXPECT_EQ(std::accumulate(b.begin(), b.end(), 0), 4000);
  EXPECT_EQ(std::accumulate(c.begin(), c.end(), 0), 9000);
}

TEST(Parallel, ArenaExecuteRunsInTheArena) {
  tbb::task_arena arena(2);
  std::vector<std::size_t> out(5000, 0);
  int concurrency = 0;
  arenaExecute(arena, [&] {
    concurrency = tbb::this_task_arena::max_concurrency();
    parallelFor(tbb::blocked_range<std::size_t>(0, out.size(), 100), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i) out[i] = i;
    });
  });
  EXPECT_EQ(concurrency, 2);
  for (std::size_t i = 0; i < out.size(); ++i) ASSERT_EQ(out[i], i);
}

}  // namespace
}  // namespace odeskin
