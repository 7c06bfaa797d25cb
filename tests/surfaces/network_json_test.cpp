// SPDX-License-Identifier: MIT
// Network files: the shipped samples load (or are refused for the reason they document), a
// description survives a write and a read, and every kind of mistake is reported with the path of
// the field, including NaN written as a bare literal.
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "engine/surfaces/network_json.hpp"
#include "surfaces/network_fixtures.hpp"

namespace odeskin {
namespace {

const std::filesystem::path kNetworks = std::filesystem::path(ODESKIN_SOURCE_DIR) / "samples/surfaces/networks";

TEST(NetworkJson, ShippedSamplesLoad) {
  for (const char* name : {"vase.json", "sheet.json", "torus.json", "patch.json", "fig4_1b_warn.json"}) {
    std::vector<std::string> warnings;
    Result<Network> n = loadNetwork(kNetworks / name, &warnings);
    ASSERT_TRUE(n.ok()) << n.status().toString();
    EXPECT_EQ(warnings.size(), std::string(name) == "fig4_1b_warn.json" ? 1u : 0u) << name;
  }
  Result<Network> refused = loadNetwork(kNetworks / "fig4_1b.json");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(refused.status().message().rfind((kNetworks / "fig4_1b.json").string() + ": patch (row 0, column 0)", 0), 0u)
      << refused.status().message();
}

TEST(NetworkJson, RoundTrip) {
  testing::SweptSurface s;
  s.closed_u = true;
  s.rows = 4;
  NetworkDescription d = testing::sweptNetwork(s, testing::mixedRowShapes());
  d.continuity = ContinuityPolicy::kWarn;
  d.shapes[5] = {0.5, 1.5, 0.5};
  Result<NetworkDescription> back = parseNetworkDescription(networkJson(d));
  ASSERT_TRUE(back.ok()) << back.status().toString();
  EXPECT_EQ(back->columns, d.columns);
  EXPECT_EQ(back->closed_u, d.closed_u);
  EXPECT_EQ(back->continuity, d.continuity);
  ASSERT_EQ(back->curve_names.size(), d.curve_names.size());
  // Curves come back in name order; compare by name.
  for (std::size_t i = 0; i < d.curve_names.size(); ++i) {
    const auto it = std::find(back->curve_names.begin(), back->curve_names.end(), d.curve_names[i]);
    ASSERT_NE(it, back->curve_names.end());
    const std::size_t j = static_cast<std::size_t>(it - back->curve_names.begin());
    EXPECT_EQ(back->curve_points[j], d.curve_points[i]);
    EXPECT_EQ(back->curve_closed[j], d.curve_closed[i]);
  }
  ASSERT_EQ(back->boundaries.size(), d.boundaries.size());
  for (std::size_t b = 0; b < d.boundaries.size(); ++b) {
    const NetworkBoundary& x = d.boundaries[b];
    const NetworkBoundary& y = back->boundaries[b];
    EXPECT_EQ(back->curve_names[y.position], d.curve_names[x.position]);
    EXPECT_EQ(y.source, x.source);
    EXPECT_EQ(y.name, x.name);
    EXPECT_EQ(y.w_first, x.w_first);
    EXPECT_EQ(y.side, x.side);
    EXPECT_EQ(y.u_lower, x.u_lower);
    EXPECT_EQ(y.slopes, x.slopes);
  }
  ASSERT_EQ(back->shapes.size(), d.shapes.size());
  for (std::size_t p = 0; p < d.shapes.size(); ++p) EXPECT_EQ(back->shapes[p].eta, d.shapes[p].eta) << p;
}

const char* kSmall = R"({
  "version": 1, "columns": 2,
  "curves": {"a": {"points": [[0,0,0],[1,0,0],[2,0,0]]}, "b": {"points": [[0,1,0],[1,1,0.5],[2,1,0]]},
             "c1": {"points": [[0,0.2,0],[1,0.2,0],[2,0.2,0]]}, "c2": {"points": [[0,0.4,0],[1,0.4,0],[2,0.4,0]]}},
  "boundaries": [{"curve": "a", "derivatives": {"controls": ["c1", "c2"], "at": [0.2, 0.4], "side": "after"}},
                 {"curve": "b", "derivatives": {"coefficients": [0, 0]}}],
  "shape": {"rho": 1, "eta": 3, "lambda": 1}
})";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(NetworkJson, ErrorsNameTheField) {
  ASSERT_TRUE(parseNetworkDescription(kSmall).ok());
  const std::pair<std::string, std::string> cases[][1] = {
      {{replaced(kSmall, "\"eta\": 3", "\"eta\": NaN"), "shape.eta: invalid JSON (line 7"}},
      {{replaced(kSmall, "\"eta\": 3", "\"eta\": NaN"), "JSON has no NaN or Infinity"}},
      {{replaced(kSmall, "[1,0,0]", "[1,-Infinity,0]"), "curves.a.points[1][1]: invalid JSON"}},
      {{replaced(kSmall, "\"eta\": 3", "\"eta\": 1e999"), "shape.eta: invalid JSON"}},
      {{replaced(kSmall, "\"eta\": 3", "\"eta\": \"3\""), "shape.eta: expected a number, got string"}},
      {{replaced(kSmall, "\"eta\": 3, ", ""), "shape.eta: missing"}},
      {{replaced(kSmall, "\"lambda\": 1", "\"lamda\": 1"), "shape.lamda: unknown field"}},
      {{replaced(kSmall, "{\"curve\": \"b\", ", "{"), "boundaries[1].curve: missing"}},
      {{replaced(kSmall, "\"curve\": \"b\"", "\"curve\": \"z\""), "boundaries[1].curve: no curve named 'z'"}},
      {{replaced(kSmall, "[0.2, 0.4]", "[0.2, 1.4]"), "boundaries[0].derivatives.at[1]: u = 1.4 is outside (0, 1)"}},
      {{replaced(kSmall, "[0.2, 0.4]", "[0.4, 0.2]"), "boundaries[0].derivatives.at: the two u must increase"}},
      {{replaced(kSmall, "\"after\"", "\"later\""), "boundaries[0].derivatives.side: expected \"after\""}},
      {{replaced(kSmall, "\"coefficients\": [0, 0]", "\"coefficients\": [0, 0], \"first\": \"a\""), "boundaries[1].derivatives: give exactly one"}},
      {{replaced(kSmall, "[[0,1,0],[1,1,0.5],[2,1,0]]", "[[0,1,0]]"), "curves.b.points: 1 points"}},
      {{replaced(kSmall, "[1,1,0.5]", "[1,1]"), "curves.b.points[1]: expected an array of 3 numbers"}},
      {{replaced(kSmall, "\"columns\": 2", "\"columns\": 0"), "columns: expected an integer in [1,"}},
      {{replaced(kSmall, "\"version\": 1", "\"version\": 2"), "version: expected 1"}},
      {{replaced(kSmall, "\"version\": 1, ", ""), "version: missing"}},
      {{replaced(kSmall, "\"shape\"", "\"patch_shapes\": [{\"row\": 1, \"column\": 0, \"rho\": 1, \"eta\": 1, \"lambda\": 1}], \"shape\""),
        "patch_shapes[0]: patch (1, 0) is outside the 1 x 2 network"}},
      {{replaced(kSmall, "\"shape\"",
                 "\"patch_shapes\": [{\"row\": 0, \"column\": 1, \"rho\": 1, \"eta\": 1, \"lambda\": 1}, "
                 "{\"row\": 0, \"column\": 1, \"rho\": 1, \"eta\": 2, \"lambda\": 1}], \"shape\""),
        "patch_shapes[1]: patch (0, 1) is already shaped by patch_shapes[0]"}},
      {{replaced(kSmall, "\"shape\"", "\"row_shapes\": [], \"shape\""), "row_shapes: expected one shape per row (1), got 0"}},
      {{replaced(kSmall, "1}\n}", "1},\n}"), "invalid JSON"}},
      {{"[1, 2]", "(top level): expected an object"}},
      {{replaced(kSmall, "\"eta\": 3", "\"eta\": 3, \"eta\": 30"), "shape.eta: appears twice in its object"}},
      {{replaced(kSmall, "\"version\": 1", "\"version\": 1, \"version\": 1"), "version: appears twice in its object"}},
  };
  for (const auto& c : cases) {
    Result<NetworkDescription> d = parseNetworkDescription(c[0].first);
    ASSERT_FALSE(d.ok()) << c[0].second;
    EXPECT_EQ(d.status().code(), StatusCode::kParseError);
    EXPECT_NE(d.status().message().find(c[0].second), std::string::npos) << d.status().message();
  }
}

// Fuzz finding (tests/fuzz/regressions/network/columns-2-24.json): columns may be up to 2^24 on
// their own, and rows x columns shapes were allocated before anything looked at the product (two
// rows: 800 MB and over 10 s; more rows: out of memory).
TEST(NetworkJson, TooManyPatchesAreRefusedBeforeAllocating) {
  Result<NetworkDescription> d = parseNetworkDescription(replaced(kSmall, "\"columns\": 2", "\"columns\": 16777216"));
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().code(), StatusCode::kParseError);
  EXPECT_EQ(d.status().message(), "columns: 1 rows x 16777216 columns = 16777216 patches, more than the 4194304 a network may have");
}

// Error messages showed the offending value with dump(), which recurses one stack frame per level:
// 300,000 nested arrays as "columns" or "version" (600 KB) crashed odeskin surface. A container is
// now shown by its kind and size.
TEST(NetworkJson, DeeplyNestedValuesAreShownByTheirKind) {
  const std::string deep = std::string(300000, '[') + std::string(300000, ']');
  Result<NetworkDescription> d = parseNetworkDescription(replaced(kSmall, "\"columns\": 2", "\"columns\": " + deep));
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().message(), "columns: expected an integer in [1, 16777216], got an array of 1 element");
  d = parseNetworkDescription(replaced(kSmall, "\"version\": 1", "\"version\": " + deep));
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().message(), "version: expected 1, got an array of 1 element");
  d = parseNetworkDescription(replaced(kSmall, "[1,1,0.5]", "{\"x\": 1}"));
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.status().message().find("curves.b.points[1]: expected an array of 3 numbers, got an object"), std::string::npos)
      << d.status().message();
}

TEST(NetworkJson, FileErrorsStartWithThePath) {
  const std::filesystem::path missing = std::filesystem::temp_directory_path() / "odeskin_no_such_network.json";
  Result<NetworkDescription> d = readNetworkDescription(missing);
  EXPECT_EQ(d.status().code(), StatusCode::kIoError);
  EXPECT_EQ(d.status().message(), missing.string() + ": cannot open for reading");
  const std::filesystem::path bad = std::filesystem::temp_directory_path() / ("odeskin_bad_network_" + std::to_string(::getpid()) + ".json");
  std::ofstream(bad) << replaced(kSmall, "\"eta\": 3", "\"eta\": NaN");
  Result<Network> n = loadNetwork(bad);
  std::filesystem::remove(bad);
  EXPECT_EQ(n.status().code(), StatusCode::kParseError);
  EXPECT_EQ(n.status().message().rfind(bad.string() + ": shape.eta: ", 0), 0u) << n.status().message();
}

}  // namespace
}  // namespace odeskin
