// SPDX-License-Identifier: MIT
#include "engine/rig/weight_rows.hpp"

#include <algorithm>
#include <map>
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

// One umbrella step as the definition reads, bone by bone in the order the rows are visited (the
// vertex, then its neighbours in the adjacency's order): what smoothRows must give bit for bit.
std::vector<WeightRow> umbrellaStep(const std::vector<WeightRow>& rows, const VertexAdjacency& a, double lambda) {
  std::vector<WeightRow> out(rows.size());
  for (std::uint32_t i = 0; i < rows.size(); ++i) {
    const auto ring = a.of(i);
    if (ring.empty()) {
      out[i] = rows[i];
      continue;
    }
    std::map<std::uint32_t, double> sum;
    for (const BoneWeight& e : rows[i]) sum[e.bone] += (1.0 - lambda) * e.weight;
    const double share = lambda / static_cast<double>(ring.size());
    for (const std::uint32_t j : ring) {
      for (const BoneWeight& e : rows[j]) sum[e.bone] += share * e.weight;
    }
    for (const auto& [bone, weight] : sum) out[i].push_back({bone, weight});
  }
  return out;
}

TEST(SmoothRows, ManyBonesMatchTheDefinitionBitForBit) {
  // Bones from 0 to 199 (four words of the bone set, some rows in the first and last only), a
  // zero weight that must stay an entry, and a lone vertex: three steps against the definition.
  constexpr std::uint32_t kVertices = 40;
  VertexAdjacency a;
  a.offsets.push_back(0);
  for (std::uint32_t v = 0; v < kVertices; ++v) {
    if (v != 17) {
      for (const std::uint32_t d : {kVertices - 2, kVertices - 1, 1u, 2u}) {
        const std::uint32_t w = (v + d) % kVertices;
        if (w != 17) a.neighbours.push_back(w);
      }
    }
    a.offsets.push_back(static_cast<std::uint32_t>(a.neighbours.size()));
  }
  std::vector<WeightRow> rows(kVertices);
  for (std::uint32_t v = 0; v < kVertices; ++v) {
    rows[v] = {{v % 7, 0.3}, {63 + v % 3, 0.1 * (1 + v % 4)}, {199 - v % 5, 1.0 / (1 + v)}};
  }
  rows[5] = {{2, 0.0}, {150, 1.0}};
  std::vector<WeightRow> expected = rows;
  for (int step = 0; step < 3; ++step) expected = umbrellaStep(expected, a, 0.5);
  smoothRows(rows, a, 3, 0.5);
  for (std::uint32_t v = 0; v < kVertices; ++v) {
    ASSERT_EQ(rows[v].size(), expected[v].size()) << "vertex " << v;
    for (std::size_t k = 0; k < rows[v].size(); ++k) {
      EXPECT_EQ(rows[v][k].bone, expected[v][k].bone) << "vertex " << v << ", entry " << k;
      EXPECT_EQ(rows[v][k].weight, expected[v][k].weight) << "vertex " << v << ", entry " << k;
    }
  }
  const auto zero = std::find_if(rows[5].begin(), rows[5].end(), [](const BoneWeight& e) { return e.bone == 2; });
  ASSERT_NE(zero, rows[5].end()) << "a bone with weight 0 keeps its entry";
}

}  // namespace
}  // namespace odeskin
