// SPDX-License-Identifier: MIT
// odeskin_deform_bench: one frame of the analytic deformation (thesis Eq 6.30, corrected) against
// plain LBS (Eq 6.1) on the same procedural arm, per backend, V and N. Every (V, N) is verified on
// every backend before it is timed. The timed work is the deformation only: the time basis and
// bone matrices of the frame are prepared once outside the loop (they cost O(B + N), not O(V)).
//   odeskin_deform_bench [--quick] [Google Benchmark flags]
// --quick (or ODESKIN_BENCH_QUICK=1) runs only V = 1e4 and 1e5 with N = 9. Without a
// --benchmark_min_time flag each case runs for at least 0.2 s, which keeps a full run on 2 cores
// under lavapipe to a few minutes.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "bench_assets.hpp"
#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/kernels/lbs_job.hpp"
#include "engine/offline/deform_player.hpp"

#ifndef ODESKIN_BUILD_TYPE
#define ODESKIN_BUILD_TYPE "unknown"
#endif

namespace odeskin::bench {
namespace {

enum class Kernel { kDeform, kLbs };
enum class Backend { kCpuRef, kCpuFast1t, kCpuFastAll, kVulkan };
constexpr Backend kBackends[] = {Backend::kCpuRef, Backend::kCpuFast1t, Backend::kCpuFastAll, Backend::kVulkan};

const char* backendName(Backend b) {
  switch (b) {
    case Backend::kCpuRef: return "cpu_ref";
    case Backend::kCpuFast1t: return "cpu_fast_1t";
    case Backend::kCpuFastAll: return "cpu_fast_all";
    case Backend::kVulkan: return "vulkan";
  }
  return "?";
}

struct Case {
  Kernel kernel = Kernel::kDeform;
  Backend backend = Backend::kCpuRef;
  std::uint32_t nominal_vertices = 0;
  int modes = 0;  // the asset's N; LBS cases reuse the last N's asset (LBS ignores it)
};

// Benchmark name -> what it measures, so the summary needs no name parsing.
std::map<std::string, Case>& cases() {
  static std::map<std::string, Case> map;
  return map;
}

// Times `body` (one frame); a failed frame skips the case with its status instead of timing garbage.
template <typename Body>
void timeLoop(benchmark::State& state, Body&& body) {
  for (auto _ : state) {
    const Status status = body();
    if (!status.ok()) {
      state.SkipWithError(status.toString().c_str());
      break;
    }
    benchmark::ClobberMemory();
  }
}

void runDeform(benchmark::State& state, BenchAsset& b, Backend backend) {
  if (backend == Backend::kCpuRef) {
    std::vector<Vec3> out(b.vertex_count);
    const FourierDeformJob job = referenceJob(b.asset, b.segment, b.basis, b.bones, out);
    timeLoop(state, [&] { return job.run(); });
    return;
  }
  if (backend == Backend::kVulkan) {
    if (!b.gpu_deformer) {
      state.SkipWithError(("no Vulkan device: " + benchDeviceNote()).c_str());
      return;
    }
    double gpu_seconds = 0.0;
    const GpuDeformFrame frame{b.segment, b.gpu_bones, b.gpu_basis};
    timeLoop(state, [&] {
      const Status status = b.gpu_deformer->run(frame);
      gpu_seconds += b.gpu_deformer->lastGpuSeconds();
      return status;
    });
    state.counters["gpu_s"] = benchmark::Counter(gpu_seconds, benchmark::Counter::kAvgIterations);
    return;
  }
  std::vector<gpu::Float4> out(b.vertex_count);
  const unsigned threads = backend == Backend::kCpuFast1t ? 1u : 0u;
  const FourierDeformFastJob job{&b.packed, b.segment, b.gpu_bones, b.gpu_basis, out, threads};
  timeLoop(state, [&] { return job.run(); });
}

void runLbs(benchmark::State& state, BenchAsset& b, Backend backend) {
  if (backend == Backend::kCpuRef) {
    std::vector<Vec3> out(b.vertex_count);
    const LbsJob job{b.asset.rest_positions, b.asset.influences, b.bones, out};
    timeLoop(state, [&] { return job.run(); });
    return;
  }
  if (backend == Backend::kVulkan) {
    if (!b.gpu_lbs) {
      state.SkipWithError(("no Vulkan device: " + benchDeviceNote()).c_str());
      return;
    }
    double gpu_seconds = 0.0;
    const GpuLbsFrame frame{b.gpu_bones};
    timeLoop(state, [&] {
      const Status status = b.gpu_lbs->run(frame);
      gpu_seconds += b.gpu_lbs->lastGpuSeconds();
      return status;
    });
    state.counters["gpu_s"] = benchmark::Counter(gpu_seconds, benchmark::Counter::kAvgIterations);
    return;
  }
  std::vector<gpu::Float4> out(b.vertex_count);
  const unsigned threads = backend == Backend::kCpuFast1t ? 1u : 0u;
  const LbsFastJob job{&b.packed, b.gpu_bones, out, threads};
  timeLoop(state, [&] { return job.run(); });
}

void runCase(benchmark::State& state, const Case& c) {
  BenchAsset& b = benchAsset(c.nominal_vertices, c.modes);  // built and verified once, untimed
  if (c.kernel == Kernel::kDeform) {
    runDeform(state, b, c.backend);
  } else {
    runLbs(state, b, c.backend);
  }
  state.counters["V"] = b.vertex_count;
  state.counters["N"] = c.kernel == Kernel::kDeform ? c.modes : 0;
  state.counters["verts_per_s"] = benchmark::Counter(b.vertex_count, benchmark::Counter::kIsIterationInvariantRate);
}

void registerCase(const Case& c) {
  const std::string name = std::string(c.kernel == Kernel::kDeform ? "deform" : "lbs") + "/" +
                           backendName(c.backend) + "/V:" + std::to_string(c.nominal_vertices) +
                           (c.kernel == Kernel::kDeform ? "/N:" + std::to_string(c.modes) : "");
  cases()[name] = c;
  // Real time: the multithreaded jobs and the GPU work outside the calling thread's CPU time.
  benchmark::RegisterBenchmark(name.c_str(), [c](benchmark::State& state) { runCase(state, c); })
      ->UseRealTime()
      ->Unit(benchmark::kMicrosecond);
}

// Grouped by V then N, so each asset is built once and LBS reuses the last N's asset.
void registerCases(bool quick) {
  const std::vector<std::uint32_t> sizes =
      quick ? std::vector<std::uint32_t>{10'000, 100'000} : std::vector<std::uint32_t>{1'000, 10'000, 100'000, 1'000'000};
  const std::vector<int> modes = quick ? std::vector<int>{9} : std::vector<int>{3, 5, 9};
  for (std::uint32_t v : sizes) {
    for (int n : modes)
      for (Backend backend : kBackends) registerCase(Case{Kernel::kDeform, backend, v, n});
    for (Backend backend : kBackends) registerCase(Case{Kernel::kLbs, backend, v, modes.back()});
  }
}

struct Measured {
  double seconds = 0.0;      // wall time per frame
  double gpu_seconds = 0.0;  // GPU timestamp time per frame (vulkan only)
  std::uint32_t vertex_count = 0;
  bool ok = false;
};

// Wraps the console reporter and keeps every finished case for the summary.
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  // Colour only on a terminal, so redirected output stays plain text.
  SummaryReporter() : ConsoleReporter(isatty(fileno(stdout)) ? OO_Defaults : OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration) continue;
      Measured m;
      m.ok = !run.error_occurred && run.iterations > 0;
      if (m.ok) {
        m.seconds = run.real_accumulated_time / static_cast<double>(run.iterations);
        if (auto it = run.counters.find("gpu_s"); it != run.counters.end()) m.gpu_seconds = it->second.value;
        if (auto it = run.counters.find("V"); it != run.counters.end()) m.vertex_count = static_cast<std::uint32_t>(it->second.value);
      }
      // function_name is the registered name, without the "/real_time" suffix.
      results_[run.run_name.function_name] = m;  // with repetitions, the last one wins
    }
    ConsoleReporter::ReportRuns(runs);
  }
  const std::map<std::string, Measured>& results() const { return results_; }

 private:
  std::map<std::string, Measured> results_;
};

void printSummary(const SummaryReporter& reporter) {
  std::map<std::pair<Backend, std::uint32_t>, Measured> lbs;
  for (const auto& [name, m] : reporter.results()) {
    const Case& c = cases().at(name);
    if (c.kernel == Kernel::kLbs && m.ok) lbs[{c.backend, c.nominal_vertices}] = m;
  }
  std::printf("\nSummary: wall time per frame (gpu = timestamp time of the dispatch), ratio = odeskin / LBS\n");
  std::printf("%-13s %9s %3s %12s %9s %11s %12s %12s %8s\n", "backend", "V", "N", "frame_us", "ns/vert", "Mvert/s",
              "gpu_us", "lbs_us", "ratio");
  for (Backend backend : kBackends) {
    for (const auto& [name, m] : reporter.results()) {
      const Case& c = cases().at(name);
      if (c.kernel != Kernel::kDeform || c.backend != backend) continue;
      if (!m.ok) {
        std::printf("%-13s %9u %3d %12s\n", backendName(backend), c.nominal_vertices, c.modes, "skipped");
        continue;
      }
      const auto it = lbs.find({backend, c.nominal_vertices});
      const double lbs_s = it != lbs.end() ? it->second.seconds : 0.0;
      char gpu_us[32] = "-";
      if (backend == Backend::kVulkan) std::snprintf(gpu_us, sizeof gpu_us, "%.1f", m.gpu_seconds * 1e6);
      char lbs_us[32] = "-";
      char ratio[32] = "-";  // no LBS case ran (filtered out or skipped)
      if (lbs_s > 0.0) {
        std::snprintf(lbs_us, sizeof lbs_us, "%.1f", lbs_s * 1e6);
        std::snprintf(ratio, sizeof ratio, "%.2f", m.seconds / lbs_s);
      }
      std::printf("%-13s %9u %3d %12.1f %9.2f %11.2f %12s %12s %8s\n", backendName(backend), m.vertex_count,
                  c.modes, m.seconds * 1e6, m.seconds * 1e9 / m.vertex_count, m.vertex_count / m.seconds * 1e-6,
                  gpu_us, lbs_us, ratio);
    }
  }
  std::printf("\nVerified before timing (worst error / box side; limit %.0e; vulkan 0 = no device):\n",
              kVerifyTolerance);
  for (const VerifiedSize& s : verifiedSizes()) {
    std::printf("  V = %7u N = %d: cpu_fast %.2e  vulkan %.2e  lbs cpu_fast %.2e  lbs vulkan %.2e  (build %.1f s)\n",
                s.vertex_count, s.modes, s.fast_error, s.gpu_error, s.lbs_fast_error, s.lbs_gpu_error,
                s.build_seconds);
  }
}

}  // namespace
}  // namespace odeskin::bench

int main(int argc, char** argv) {
  using namespace odeskin::bench;
  const char* quick_env = std::getenv("ODESKIN_BENCH_QUICK");
  bool quick = quick_env != nullptr && std::strcmp(quick_env, "0") != 0 && *quick_env != '\0';
  bool has_min_time = false;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      quick = true;
      continue;
    }
    if (std::strncmp(argv[i], "--benchmark_min_time", 20) == 0) has_min_time = true;
    args.push_back(argv[i]);
  }
  static char default_min_time[] = "--benchmark_min_time=0.2";
  if (!has_min_time) args.push_back(default_min_time);
  int count = static_cast<int>(args.size());
  args.push_back(nullptr);
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 1;

  std::printf("odeskin_deform_bench: build type %s, %u hardware threads (cpu_fast_all), Vulkan device: %s%s\n",
              ODESKIN_BUILD_TYPE, std::thread::hardware_concurrency(), benchDeviceNote().c_str(),
              quick ? ", quick run" : "");
  registerCases(quick);
  SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  printSummary(reporter);
  releaseAll();
  benchmark::Shutdown();
  return 0;
}
