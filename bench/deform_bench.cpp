// SPDX-License-Identifier: MIT
// odeskin_deform_bench: one frame of the analytic deformation (thesis Eq 6.30, corrected) against
// plain LBS (Eq 6.1) on the same procedural arm, per backend, V and N. Every (V, N) is verified on
// every backend before it is timed. The timed work is the deformation only: the time basis and
// bone matrices of the frame are prepared once outside the loop (they cost O(B + N), not O(V)).
//   odeskin_deform_bench [--quick] [--cat=DIR] [Google Benchmark flags]
// --cat=DIR (shared/data/cat-poses) adds the cat, fitted by the whole pipeline, as a first size.
// --quick (or ODESKIN_BENCH_QUICK=1) runs only V = 1e4, 32,185 and 1e5 with N = 9. Without a
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
// cpu_fast: FourierDeformFastJob / LbsFastJob (one vertex at a time, the shader's code);
// cpu_kernel: CpuDeformKernel::deform / skin (sorted 16-vertex blocks, SIMD).
enum class Backend { kCpuRef, kCpuFast1t, kCpuFastAll, kCpuKernel1t, kCpuKernelAll, kVulkan };
constexpr Backend kBackends[] = {Backend::kCpuRef,      Backend::kCpuFast1t,    Backend::kCpuFastAll,
                                 Backend::kCpuKernel1t, Backend::kCpuKernelAll, Backend::kVulkan};

const char* backendName(Backend b) {
  switch (b) {
    case Backend::kCpuRef: return "cpu_ref";
    case Backend::kCpuFast1t: return "cpu_fast_1t";
    case Backend::kCpuFastAll: return "cpu_fast_all";
    case Backend::kCpuKernel1t: return "cpu_kernel_1t";
    case Backend::kCpuKernelAll: return "cpu_kernel_all";
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

// Names in registration order (V ascending), the summary's row order.
std::vector<std::string>& caseOrder() {
  static std::vector<std::string> order;
  return order;
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

// Times gpu.run(frame) (submit and wait) and reports the dispatch's timestamp-query time per
// iteration as the counter gpu_s.
template <typename Gpu, typename Frame>
void timeGpuLoop(benchmark::State& state, Gpu& gpu, const Frame& frame) {
  double gpu_seconds = 0.0;
  timeLoop(state, [&] {
    Status status = gpu.run(frame);
    gpu_seconds += gpu.lastGpuSeconds();
    return status;
  });
  state.counters["gpu_s"] = benchmark::Counter(gpu_seconds, benchmark::Counter::kAvgIterations);
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
    timeGpuLoop(state, *b.gpu_deformer, GpuDeformFrame{b.segment, b.gpu_bones, b.gpu_basis});
    return;
  }
  std::vector<gpu::Float4> out(b.vertex_count);
  if (backend == Backend::kCpuKernel1t || backend == Backend::kCpuKernelAll) {
    const unsigned threads = backend == Backend::kCpuKernel1t ? 1u : 0u;
    timeLoop(state, [&] { return b.kernel->deform(b.segment, b.gpu_bones, b.gpu_basis, out, threads); });
    return;
  }
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
    timeGpuLoop(state, *b.gpu_lbs, GpuLbsFrame{b.gpu_bones});
    return;
  }
  std::vector<gpu::Float4> out(b.vertex_count);
  if (backend == Backend::kCpuKernel1t || backend == Backend::kCpuKernelAll) {
    const unsigned threads = backend == Backend::kCpuKernel1t ? 1u : 0u;
    timeLoop(state, [&] { return b.kernel->skin(b.gpu_bones, out, threads); });
    return;
  }
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
                           backendName(c.backend) + "/V:" +
                           (c.nominal_vertices == kCatVertices ? std::string("cat") : std::to_string(c.nominal_vertices)) +
                           (c.kernel == Kernel::kDeform ? "/N:" + std::to_string(c.modes) : "");
  cases()[name] = c;
  caseOrder().push_back(name);
  // Real time: the multithreaded jobs and the GPU work outside the calling thread's CPU time.
  benchmark::RegisterBenchmark(name.c_str(), [c](benchmark::State& state) { runCase(state, c); })
      ->UseRealTime()
      ->Unit(benchmark::kMicrosecond);
}

// Grouped by V then N, so each asset is built once and LBS reuses the last N's asset.
void registerCases(bool quick) {
  // 32,185: the thesis's "Runner" (its 0.79 ms solver + skin deformer figure), issue 6's target size.
  const std::vector<std::uint32_t> sizes = quick ? std::vector<std::uint32_t>{10'000, 32'185, 100'000}
                                                 : std::vector<std::uint32_t>{1'000, 10'000, 32'185, 100'000, 1'000'000};
  const std::vector<int> modes = quick ? std::vector<int>{9} : std::vector<int>{3, 5, 9, 17};
  std::vector<std::uint32_t> all_sizes = sizes;
  if (hasCatDirectory()) all_sizes.insert(all_sizes.begin(), kCatVertices);
  for (std::uint32_t v : all_sizes) {
    for (int n : modes)
      for (Backend backend : kBackends) registerCase(Case{Kernel::kDeform, backend, v, n});
    for (Backend backend : kBackends) registerCase(Case{Kernel::kLbs, backend, v, modes.back()});
  }
}

struct Measured {
  double seconds = 0.0;      // wall time per frame
  double cpu_seconds = 0.0;  // CPU time of the calling thread per frame (what preemption does not inflate)
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
        m.cpu_seconds = run.cpu_accumulated_time / static_cast<double>(run.iterations);
        if (auto it = run.counters.find("gpu_s"); it != run.counters.end()) m.gpu_seconds = it->second.value;
        if (auto it = run.counters.find("V"); it != run.counters.end()) m.vertex_count = static_cast<std::uint32_t>(it->second.value);
      }
      // function_name is the registered name, without the "/real_time" suffix.
      // With --benchmark_repetitions, the fastest repetition: on a shared machine the slower ones
      // measure the other processes.
      auto [it, added] = results_.try_emplace(run.run_name.function_name, m);
      if (!added && m.ok && (!it->second.ok || m.seconds < it->second.seconds)) it->second = m;
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
  std::printf("\nSummary: wall time per frame (gpu = timestamp time of the dispatch), ratio = odeskin / LBS;\n"
              "cpu_us, cpu_ratio: the calling thread's CPU time instead (1-thread cases on a busy machine)\n");
  std::printf("%-14s %9s %3s %12s %9s %11s %12s %12s %8s %10s %9s\n", "backend", "V", "N", "frame_us", "ns/vert",
              "Mvert/s", "gpu_us", "lbs_us", "ratio", "cpu_us", "cpu_ratio");
  for (Backend backend : kBackends) {
    for (const std::string& name : caseOrder()) {
      const auto found = reporter.results().find(name);
      if (found == reporter.results().end()) continue;  // filtered out
      const Measured& m = found->second;
      const Case& c = cases().at(name);
      if (c.kernel != Kernel::kDeform || c.backend != backend) continue;
      if (!m.ok) {
        std::printf("%-14s %9u %3d %12s\n", backendName(backend), c.nominal_vertices, c.modes, "skipped");
        continue;
      }
      const auto it = lbs.find({backend, c.nominal_vertices});
      const double lbs_s = it != lbs.end() ? it->second.seconds : 0.0;
      const double lbs_cpu_s = it != lbs.end() ? it->second.cpu_seconds : 0.0;
      char gpu_us[32] = "-";
      if (backend == Backend::kVulkan) std::snprintf(gpu_us, sizeof gpu_us, "%.1f", m.gpu_seconds * 1e6);
      char lbs_us[32] = "-";
      char ratio[32] = "-";  // no LBS case ran (filtered out or skipped)
      char cpu_ratio[32] = "-";
      if (lbs_s > 0.0) {
        std::snprintf(lbs_us, sizeof lbs_us, "%.1f", lbs_s * 1e6);
        std::snprintf(ratio, sizeof ratio, "%.2f", m.seconds / lbs_s);
      }
      if (lbs_cpu_s > 0.0) std::snprintf(cpu_ratio, sizeof cpu_ratio, "%.2f", m.cpu_seconds / lbs_cpu_s);
      std::printf("%-14s %9u %3d %12.1f %9.2f %11.2f %12s %12s %8s %10.1f %9s\n", backendName(backend),
                  m.vertex_count, c.modes, m.seconds * 1e6, m.seconds * 1e9 / m.vertex_count,
                  m.vertex_count / m.seconds * 1e-6, gpu_us, lbs_us, ratio, m.cpu_seconds * 1e6, cpu_ratio);
    }
  }
  std::printf("\nVerified before timing (worst error / box side; limit %.0e; vulkan 0 = no device):\n",
              kVerifyTolerance);
  for (const VerifiedSize& s : verifiedSizes()) {
    std::printf("  V = %7u N = %2d: cpu_fast %.2e  cpu_kernel %.2e  vulkan %.2e  lbs cpu_fast %.2e  lbs cpu_kernel "
                "%.2e  lbs vulkan %.2e  (build %.1f s)\n",
                s.vertex_count, s.modes, s.fast_error, s.kernel_error, s.gpu_error, s.lbs_fast_error,
                s.lbs_kernel_error, s.lbs_gpu_error, s.build_seconds);
  }
  std::printf("\ncpu_kernel blocks of 16 lanes (padding: lanes computed and not written, as a share of V):\n");
  for (const VerifiedSize& s : verifiedSizes()) {
    const CpuDeformKernel::Stats& k = s.kernel_stats;
    std::printf("  V = %7u N = %2d: %s, %zu blocks, %.1f%% padding, %.1f%% two-curve blocks, %.2f bones per block, "
                "%.1f MB\n",
                s.vertex_count, s.modes, cpuKernelArchName(s.kernel_arch), k.blocks,
                100.0 * (static_cast<double>(k.lanes) / s.vertex_count - 1.0),
                100.0 * static_cast<double>(k.two_curve_blocks) / static_cast<double>(k.blocks), k.mean_union_bones,
                static_cast<double>(k.bytes) * 1e-6);
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
    // Google Benchmark prints its own flags and exits; this program's two come first.
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::printf(
          "odeskin_deform_bench [--quick] [--cat=DIR] [Google Benchmark flags]\n"
          "  --quick     V = 1e4, 32,185 and 1e5 with N = 9 only (also ODESKIN_BENCH_QUICK=1)\n"
          "  --cat=DIR   also the cat of DIR (shared/data/cat-poses), fitted by the whole pipeline\n"
          "Without --benchmark_min_time each case runs for at least 0.2 s.\n\n");
    }
    if (std::strcmp(argv[i], "--quick") == 0) {
      quick = true;
      continue;
    }
    if (std::strncmp(argv[i], "--cat=", 6) == 0) {
      setCatDirectory(argv[i] + 6);
      continue;
    }
    if (std::strncmp(argv[i], "--benchmark_min_time", 20) == 0) has_min_time = true;
    args.push_back(argv[i]);
  }
  if (!has_min_time) {
    static char default_min_time[] = "--benchmark_min_time=0.2";  // static: argv outlives this block
    args.push_back(default_min_time);
  }
  int count = static_cast<int>(args.size());
  args.push_back(nullptr);
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 1;

  std::printf("odeskin_deform_bench: build type %s, %u hardware threads (cpu_*_all), Vulkan device: %s%s\n",
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
