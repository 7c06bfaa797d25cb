// SPDX-License-Identifier: MIT
// What each per-frame output costs the CPU runtime: one frame of 16 cats (shared/data/cat-poses,
// fitted by the whole pipeline, N = 9) on one thread, with positions only, with normals, and with
// normals and tangents (RuntimeOptions::tangents). The tangents are a smooth field across the
// surface standing in for an engine's glTF tangents; their cost does not depend on their values.
//
//   build/bench/odeskin_runtime_outputs_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "engine/io/obj_reader.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "engine/runtime/cpu_runtime.hpp"
#include "engine/runtime/instance_outputs.hpp"

namespace odeskin::bench {
namespace {

constexpr std::uint32_t kInstances = 16;

// Unit tangents orthogonal to each vertex's normal (the runtime's own, of the rest mesh), turning
// across the surface.
std::vector<gpu::Float4> tangentField(const RuntimeAsset& plain) {
  const std::vector<gpu::Float4>& rest = plain.packed().rest_positions;
  std::vector<gpu::Float4> normals(rest.size());
  computeVertexNormals(plain.cornerOffsets(), plain.corners(), rest, normals);
  std::vector<gpu::Float4> out(rest.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double turn = 0.01 * static_cast<double>(i);
    const Vec3 axis = glm::normalize(Vec3(std::cos(turn), std::sin(turn), 0.5));
    const Vec3 n(normals[i].x, normals[i].y, normals[i].z);
    const Vec3 t = axis - n * glm::dot(n, axis);
    const double length = glm::length(t);
    out[i] = length > 1e-6 ? gpu::Float4{static_cast<float>(t.x / length), static_cast<float>(t.y / length),
                                         static_cast<float>(t.z / length), 1.0f}
                           : gpu::Float4{0.0f, 0.0f, 0.0f, 1.0f};
  }
  return out;
}

// The cat asset with tangents, fitted once; exits with a message when the data are missing.
const RuntimeAsset& catAsset() {
  static std::optional<RuntimeAsset> asset;
  if (asset) return *asset;
  std::vector<std::filesystem::path> poses;
  poses.reserve(10);
  for (int k = 0; k < 10; ++k) poses.push_back(std::string(ODESKIN_DATA_DIR) + "/cat-poses/cat-0" + std::to_string(k) + ".obj");
  Result<ExampleSet> examples = readObjSequence(poses);
  Result<PipelineResult> fitted = examples.ok() ? runFitPipeline(*examples, PipelineOptions{}) : Result<PipelineResult>(examples.status());
  if (!fitted.ok()) {
    std::fprintf(stderr, "odeskin_runtime_outputs_bench: %s\n", fitted.status().toString().c_str());
    std::_Exit(1);  // not exit(), which is not thread-safe
  }
  Result<RuntimeAsset> plain = RuntimeAsset::create(fitted->asset);
  RuntimeAssetOptions options;
  if (plain.ok()) options.render_tangents = tangentField(*plain);
  Result<RuntimeAsset> made = plain.ok() ? RuntimeAsset::create(fitted->asset, options) : std::move(plain);
  if (!made.ok()) {
    std::fprintf(stderr, "odeskin_runtime_outputs_bench: %s\n", made.status().toString().c_str());
    std::_Exit(1);  // not exit(), which is not thread-safe
  }
  asset.emplace(std::move(made).value());
  return *asset;
}

void frame(benchmark::State& state, bool normals, bool tangents) {
  RuntimeOptions options;
  options.capacity = kInstances;
  options.normals = normals;
  options.tangents = tangents;
  options.threads = 1;
  Result<CpuRuntime> rt = CpuRuntime::create(catAsset(), options);
  if (!rt.ok() || !rt->setInstanceCount(kInstances).ok()) {
    state.SkipWithError(rt.status().toString().c_str());
    return;
  }
  for (std::uint32_t k = 0; k < kInstances; ++k) {
    if (!rt->setInstance(k, InstanceState::atTime(0.5 * k + 0.25)).ok()) state.SkipWithError("setInstance");
  }
  while (state.KeepRunning()) {
    const Result<std::uint64_t> f = rt->submitFrame();
    if (!f.ok()) {
      state.SkipWithError(f.status().toString().c_str());
      break;
    }
    benchmark::ClobberMemory();
  }
  state.counters["vertices/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * kInstances *
                                                        catAsset().vertexCount(),
                                                    benchmark::Counter::kIsRate);
}

void positionsOnly(benchmark::State& state) { frame(state, false, false); }
void withNormals(benchmark::State& state) { frame(state, true, false); }
void withNormalsAndTangents(benchmark::State& state) { frame(state, true, true); }

BENCHMARK(positionsOnly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(withNormals)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(withNormalsAndTangents)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace odeskin::bench

BENCHMARK_MAIN();
