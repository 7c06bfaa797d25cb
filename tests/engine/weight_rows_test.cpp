// SPDX-License-Identifier: MIT
#include "engine/rig/weight_rows.hpp"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

namespace odeskin {
namespace {

// A path 0 - 1 - 2 - 3 and a lone vertex 4, as compressed rows.
VertexAdjacency pathAndLoneVertex() {
  VertexAdjacency a;
  a.offsets = {0, 1, 3, 5, 6, 6};
  a.neighbours = {1, 0, 2, 1, 3, 2};
  return a;
}

void expectRow(const WeightRow& row, const std::vector<BoneWeight>& expected, const char* what) {
  ASSERT_EQ(row.size(), expected.size()) << what;
  for (std::size_t k = 0; k < row.size(); ++k) {
    EXPECT_EQ(row[k].bone, expected[k].bone) << what << ", entry " << k;
    EXPECT_DOUBLE_EQ(row[k].weight, expected[k].weight) << what << ", entry " << k;
  }
}

TEST(SmoothRows, OneUmbrellaStepByHand) {
  // Bones out of their neighbours' order on purpose: each output row must come back sorted by
  // bone with every bone once.
  std::vector<WeightRow> rows = {{{7, 1.0}}, {{2, 0.25}, {7, 0.75}}, {{2, 1.0}}, {{5, 1.0}}, {{9, 1.0}}};
  smoothRows(rows, pathAndLoneVertex(), 1, 0.5);
  // w_i <- 0.5 w_i + 0.5 mean of the neighbours' rows.
  expectRow(rows[0], {{2, 0.125}, {7, 0.5 + 0.375}}, "vertex 0");
  expectRow(rows[1], {{2, 0.125 + 0.25}, {7, 0.375 + 0.25}}, "vertex 1");
  expectRow(rows[2], {{2, 0.5 + 0.0625}, {5, 0.25}, {7, 0.1875}}, "vertex 2");
  expectRow(rows[3], {{2, 0.5}, {5, 0.5}}, "vertex 3");
  expectRow(rows[4], {{9, 1.0}}, "vertex 4 (no neighbours: unchanged)");
}

TEST(SmoothRows, KeepsEachRowsSumAndSign) {
  // A ring of 12 vertices, each with three neighbours on either side, and rows of up to 20 bones:
  // more entries than one row holds, so bones repeat across the ring many times over.
  constexpr std::uint32_t kVertices = 12;
  VertexAdjacency a;
  a.offsets.push_back(0);
  for (std::uint32_t v = 0; v < kVertices; ++v) {
    for (std::uint32_t d : {kVertices - 3, kVertices - 2, kVertices - 1, 1u, 2u, 3u}) a.neighbours.push_back((v + d) % kVertices);
    a.offsets.push_back(static_cast<std::uint32_t>(a.neighbours.size()));
  }
  std::vector<WeightRow> rows(kVertices);
  for (std::uint32_t v = 0; v < kVertices; ++v) {
    const std::uint32_t count = 1 + v % 5;
    for (std::uint32_t k = 0; k < count; ++k) rows[v].push_back({(v * 7 + k * 3) % 20, 1.0 / count});
    std::sort(rows[v].begin(), rows[v].end(), [](const BoneWeight& x, const BoneWeight& y) { return x.bone < y.bone; });
  }
  smoothRows(rows, a, 10, 0.5);
  for (std::uint32_t v = 0; v < kVertices; ++v) {
    double sum = 0.0;
    for (std::size_t k = 0; k < rows[v].size(); ++k) {
      EXPECT_GE(rows[v][k].weight, 0.0) << "vertex " << v;
      if (k > 0) {
        EXPECT_LT(rows[v][k - 1].bone, rows[v][k].bone) << "vertex " << v << ": not sorted, or a bone twice";
      }
      sum += rows[v][k].weight;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << "vertex " << v;
  }
}

}  // namespace
}  // namespace odeskin
