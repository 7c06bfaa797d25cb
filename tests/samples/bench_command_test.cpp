// SPDX-License-Identifier: MIT
// `odeskin bench` end to end: the report files exist with the layout, the quick cases are
// there (odeskin and lbs at 32,185 vertices, N = 9, cpu_fast 1 thread and vulkan), and bad options
// or outputs fail cleanly with no file left behind.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "command_test_support.hpp"
#include "engine/core/thread_count.hpp"
#include "host/gpu_test_support.hpp"
#include "samples/odeskin/bench_command.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using testing::Captured;
using testing::CommandCase;
using testing::scratchDir;

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

bool hasRecord(const nlohmann::json& j, const std::string& kernel, const std::string& backend, unsigned threads,
               std::size_t vertices, int terms) {
  for (const auto& r : j["records"]) {
    if (r["case"] == kernel && r["backend"] == backend && r["threads"] == threads && r["vertices"] == vertices &&
        r["terms"] == terms && r["seconds_per_frame"].get<double>() > 0.0) {
      return true;
    }
  }
  return false;
}

TEST(BenchCommand, WithoutDataTilesTheProceduralArmOnCpuBackends) {
  const fs::path dir = scratchDir("odeskin_bench_", "arm");
  BenchCommandOptions o;
  o.json = dir / "out.json";
  o.csv = dir / "out.csv";
  o.plot = dir / "out.png";
  o.data = "none";
  o.sizes = {3000};
  o.terms = {3};
  o.backends = "cpu_ref,cpu_fast";
  o.threads = 100000;  // more than any machine runs: the all-threads records say what ran
  o.min_time = 0.01;
  Captured io;
  ASSERT_EQ(runBenchCommand(o, io.console), kExitOk) << io.err.str();
  const nlohmann::json j = readJson(o.json);
  EXPECT_EQ(j["device"], "none (not requested)");
  EXPECT_EQ(j["device_copy"]["note"], "not measured: no Vulkan device in this run");
  EXPECT_NE(j["mesh"].get<std::string>().find("procedural arm"), std::string::npos);
  for (const char* backend : {"cpu_ref", "cpu_fast"}) {
    EXPECT_TRUE(hasRecord(j, "odeskin", backend, 1, 3000, 3)) << backend;
    EXPECT_TRUE(hasRecord(j, "lbs", backend, 1, 3000, 0)) << backend;
    EXPECT_TRUE(hasRecord(j, "dqs", backend, 1, 3000, 0)) << backend;
  }
  const unsigned machine = usableThreads(0);
  if (machine > 1) {
    EXPECT_TRUE(hasRecord(j, "odeskin", "cpu_fast", machine, 3000, 3));
  }
  for (const auto& r : j["records"]) EXPECT_LE(r["threads"].get<unsigned>(), machine) << r.dump();
  EXPECT_NE(io.err.str().find("--threads 100000: this machine runs at most " + std::to_string(machine)), std::string::npos)
      << io.err.str();
  EXPECT_TRUE(j["fit_stages"].empty());  // no data: no stage table
  EXPECT_TRUE(fs::file_size(o.csv) > 0 && fs::file_size(o.plot) > 0);
  EXPECT_EQ(io.out.str().find("odeskin N=9 / lbs"), std::string::npos);  // no N = 9 case here
  fs::remove_all(dir);
}

class BenchCommandGpu : public testing::GpuTest {};

TEST_F(BenchCommandGpu, QuickCasesOnTheCatIncludeVulkan) {
  const fs::path dir = scratchDir("odeskin_bench_", "cat");
  BenchCommandOptions o;
  o.json = dir / "quick.json";
  o.data = ODESKIN_DATA_DIR;
  o.sizes = {32'185};
  o.terms = {9};
  o.backends = "cpu_fast,vulkan";
  o.threads = 1;
  o.min_time = 0.01;
  o.validation = true;
  o.fit = false;
  Captured io;
  ASSERT_EQ(runBenchCommand(o, io.console), kExitOk) << io.err.str();
  const nlohmann::json j = readJson(o.json);
  EXPECT_NE(j["mesh"].get<std::string>().find("cat-poses"), std::string::npos);
  EXPECT_NE(j["device"].get<std::string>().find(device().name()), std::string::npos);
  for (const char* backend : {"cpu_fast", "vulkan"}) {
    EXPECT_TRUE(hasRecord(j, "odeskin", backend, 1, 32'185, 9)) << backend;
    EXPECT_TRUE(hasRecord(j, "lbs", backend, 1, 32'185, 0)) << backend;
  }
  // The fits that made the mesh are in the stage table even with --no-fit.
  ASSERT_EQ(j["fit_stages"].size(), 1u);
  EXPECT_EQ(j["fit_stages"][0]["vertices"], 7207);
  EXPECT_NE(io.out.str().find("targets (issue 6, from this run)"), std::string::npos);
  // Frame traffic per record, set against the device's measured copy rate.
  EXPECT_GT(j["device_copy"]["bytes_per_second"].get<double>(), 0.0);
  for (const auto& r : j["records"]) EXPECT_GT(r["bytes_per_second"].get<double>(), 0.0) << r["case"] << r["backend"];
  // Under the validation layer the Vulkan times include its checks: recorded, and not judged.
  EXPECT_EQ(j["validation"], true);
  EXPECT_NE(io.out.str().find("(validation layer on)"), std::string::npos);
  EXPECT_NE(io.out.str().find("vulkan 1 thread, 32185 vertices: "), std::string::npos);
  EXPECT_NE(io.out.str().find("not judged: the validation layer's checks are in the Vulkan times"), std::string::npos);
  fs::remove_all(dir);
}

TEST(BenchCommand, RejectsBadOptionsAndUnwritableOutputs) {
  const fs::path dir = scratchDir("odeskin_bench_", "bad");
  BenchCommandOptions base;
  base.json = dir / "out.json";
  base.data = "none";
  base.sizes = {100};
  base.terms = {3};
  base.backends = "cpu_fast";
  std::vector<CommandCase<BenchCommandOptions>> usage;
  usage.push_back({base, "--backends must be auto or a list"});
  usage.back().options.backends = "gpu";
  usage.push_back({base, "--backends must be auto or a list"});
  usage.back().options.backends = "cpu_fast,";
  usage.push_back({base, "--sizes must be in"});
  usage.back().options.sizes = {0};
  usage.push_back({base, "--terms must be in"});
  usage.back().options.terms = {65};
  usage.push_back({base, "--min-time must be"});
  usage.back().options.min_time = -1.0;
  usage.push_back({base, "--min-time must be in [0, 3600] seconds, got 1e+09"});
  usage.back().options.min_time = 1e9;
  usage.push_back({base, "--sizes lists 100 twice"});
  usage.back().options.sizes = {100, 200, 100};
  usage.push_back({base, "--terms lists 3 twice"});
  usage.back().options.terms = {3, 3};
  usage.push_back({base, "--data " + (dir / "no-data-here").string() + " has no cat-poses folder"});
  usage.back().options.data = dir / "no-data-here";
  usage.push_back({base, "two outputs would be " + (dir / "out.json").string()});
  usage.back().options.csv = dir / "out.json";
  usage.push_back({base, "--fit-plot draws the fitting stages, which --no-fit leaves out"});
  usage.back().options.fit_plot = dir / "fit.png";
  usage.back().options.fit = false;
  auto run = [](const BenchCommandOptions& o, Captured& io) { return runBenchCommand(o, io.console); };
  testing::expectRejected(usage, run, kExitUsage, "bench");
  std::vector<CommandCase<BenchCommandOptions>> failures;
  failures.push_back({base, "file.txt/out.json: cannot create directory"});
  failures.back().options.json = dir / "file.txt" / "out.json";
  std::ofstream(dir / "file.txt") << "not a folder";
  testing::expectRejected(failures, run, kExitFailure, "bench");
  EXPECT_FALSE(fs::exists(dir / "out.json"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace odeskin
