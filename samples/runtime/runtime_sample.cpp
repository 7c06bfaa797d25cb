// SPDX-License-Identifier: MIT
// odeskin_runtime_sample: how a game engine drives the runtime (issue 6 point 1). Loads the cat
// (fitted from shared/data/cat-poses at start-up, or a .odsk given on the command line), animates
// N instances (default 1,000) for S seconds (default 10) of simulated time at 60 Hz, each with its
// own time offset and material preset, every fourth with bones from "the engine" (the asset's
// bones placed in the world), and prints per-frame host and GPU times (timestamp queries) and
// totals. It checks itself at the end: two instances of the last frame against the
// double-precision reference, within 1e-5 of the box. With --record it plays the engine's part
// too: each frame is recorded into its own command buffers, which it submits (EngineSubmissions).
// --backend auto runs on Vulkan where the device opens and the runtime builds on it, else on the CPU
// with a note; a Vulkan failure during the frames still ends the run.
// Exit status: 0 success; 1 failure (no Vulkan device for --backend vulkan, bad asset, failed
// check), with one line "odeskin_runtime_sample: error: ..."; 2 usage error.
// docs/runtime.md quotes the part between the snippet markers; a test keeps the two identical.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine/core/thread_count.hpp"
#include "engine/io/asset_file.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/kernels/packed_deform.hpp"
#include "engine/offline/residual_fit.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "engine/runtime/cpu_runtime.hpp"
#include "host/device.hpp"
#include "host/runtime/vulkan_runtime.hpp"
#include "samples/runtime/engine_submissions.hpp"
#include "samples/decimal_integers.hpp"
#include "samples/standard_output.hpp"

namespace odeskin {
namespace {

constexpr double kHz = 60.0;
constexpr double kCheckTolerance = 1e-5;  // x the longest box side

struct SampleOptions {
  std::string backend = "vulkan";
  std::uint32_t instances = 1000;
  double seconds = 10.0;
  std::filesystem::path asset;  // empty: fit the cat
  std::filesystem::path data = ODESKIN_SAMPLE_DATA_DIR;
  std::string device = "auto";
  bool validation = false;
  unsigned threads = 0;
  bool quiet = false;
  bool record = false;  // Vulkan: frames recorded into the sample's command buffers (EngineSubmissions)
  std::string bounds = "auto";  // Vulkan: how the host reads the boxes (BoundsReadback)
};

BoundsReadback readback(const std::string& name) {
  if (name == "mapped") return BoundsReadback::kMapped;
  return name == "staged" ? BoundsReadback::kStaged : BoundsReadback::kAuto;
}

int fail(const Status& status) {
  std::fprintf(stderr, "odeskin_runtime_sample: error: %s\n", status.message().c_str());
  return 1;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The cat from its ten example poses with the automatic rig and the skin material (~1 s).
Result<DeformAsset> fitCat(const std::filesystem::path& data) {
  std::vector<std::filesystem::path> poses;
  poses.reserve(10);
  for (int k = 0; k < 10; ++k) poses.push_back(data / "cat-poses" / ("cat-0" + std::to_string(k) + ".obj"));
  ODESKIN_ASSIGN_OR_RETURN(ExampleSet examples, readObjSequence(poses));
  PipelineOptions options;
  options.material = skinMaterial();
  ODESKIN_ASSIGN_OR_RETURN(PipelineResult fitted, runFitPipeline(examples, options));
  return std::move(fitted.asset);
}

// "The engine's animation system": the asset's own bones at time t, placed on a grid in the world
// (a rotation about y and a translation composed after every bone).
void engineBones(const RuntimeAsset& asset, double t, std::uint32_t instance, std::span<gpu::BoneMatrix> out) {
  const auto [segment, tau] = asset.locate(t);
  asset.bonesAt(segment, tau, out);
  const float angle = 0.1f * static_cast<float>(instance);
  const float c = std::cos(angle), s = std::sin(angle);
  // NOLINTNEXTLINE(bugprone-integer-division): instance / 32 is the grid row, an integer on purpose
  const float x = 3.0f * static_cast<float>(instance % 32), z = 3.0f * static_cast<float>(instance / 32);
  for (gpu::BoneMatrix& m : out) {
    const gpu::Float4 r0 = m.row0, r2 = m.row2;
    m.row0 = {c * r0.x + s * r2.x, c * r0.y + s * r2.y, c * r0.z + s * r2.z, c * r0.w + s * r2.w + x};
    m.row2 = {-s * r0.x + c * r2.x, -s * r0.y + c * r2.y, -s * r0.z + c * r2.z, -s * r0.w + c * r2.w + z};
  }
}

struct Totals {
  double host = 0.0, prepare = 0.0, deform = 0.0, worst_host = 0.0, worst_deform = 0.0, read_bounds = 0.0;
  std::uint64_t frames = 0, bounds_reads = 0;
};

void report(const FrameTimes& t, std::uint64_t frame, double set_seconds, bool gpu, bool quiet, Totals& totals) {
  totals.host += set_seconds + t.submit_seconds;
  totals.prepare += t.prepare_seconds;
  totals.deform += t.deform_seconds;
  totals.worst_host = std::max(totals.worst_host, set_seconds + t.submit_seconds);
  totals.worst_deform = std::max(totals.worst_deform, t.deform_seconds);
  ++totals.frames;
  if (quiet) return;
  std::printf("frame %5llu  host %8.3f ms (set %.3f, prepare %.3f, submit %.3f)  %s %9.3f ms\n",
              static_cast<unsigned long long>(frame), 1e3 * (set_seconds + t.submit_seconds), 1e3 * set_seconds,
              1e3 * t.prepare_seconds, 1e3 * t.submit_seconds, gpu ? "gpu" : "cpu deform", 1e3 * t.deform_seconds);
  std::fflush(stdout);
}

// Instance k of frame f: its own phase through the clip, its preset, and every fourth the engine's bones.
InstanceState stateOf(const RuntimeAsset& asset, std::uint32_t k, double seconds, std::span<const gpu::BoneMatrix> bones) {
  const double offset = std::fmod(0.6180339887 * k, 1.0) * asset.endTime();
  const double t = std::fmod(offset + seconds / asset.segmentSeconds(), asset.endTime());
  InstanceState state = InstanceState::atTime(t).withPreset(k % asset.presetCount());
  return k % 4 == 3 ? state.withBones(bones) : state;
}

// Instance `k` of the last frame against the double-precision reference of what it played.
Result<double> checkInstance(DeformRuntime& rt, std::uint64_t frame, std::uint32_t k, double seconds,
                             std::span<gpu::BoneMatrix> bones) {
  const RuntimeAsset& asset = rt.asset();
  const InstanceState state = stateOf(asset, k, seconds, bones);
  const auto [segment, tau] = asset.locate(state.time);
  // Preset 1 is the static preset (run() adds it); preset 0 the asset's own materials.
  DeformAsset played = asset.source();
  if (state.preset > 0) {
    ODESKIN_ASSIGN_OR_RETURN(played, assetWithPreset(asset.source(), staticPreset()));
  }
  ODESKIN_ASSIGN_OR_RETURN(DeformPlayer player, DeformPlayer::create(played));
  std::vector<ModeBasisValue> basis(player.basisSize());
  std::vector<BoneTransform> matrices(asset.boneCount());
  player.basisAt(tau, basis);
  if (state.bones.empty()) {
    player.bonesAt(played, segment, tau, matrices);
  } else {
    for (std::size_t b = 0; b < matrices.size(); ++b) matrices[b] = fromGpuBone(bones[b]);
  }
  std::vector<Vec3> expected(asset.vertexCount());
  ODESKIN_TRY(referenceJob(played, segment, basis, matrices, expected).run());
  std::vector<gpu::Float4> actual(asset.vertexCount());
  ODESKIN_TRY(rt.readPositions(frame, k, actual));
  double worst = 0.0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    worst = std::max(worst, glm::length(Vec3(actual[i].x, actual[i].y, actual[i].z) - expected[i]));
  }
  return worst / longestBoxSide(asset.source().rest_positions);
}

// --backend auto: a Vulkan failure while setting up (no device, out of memory, device lost) means
// the CPU runtime, with a note; as odeskin play does.
bool fallsBackToCpu(const SampleOptions& o, const Status& failure) {
  const StatusCode code = failure.code();
  if (o.backend != "auto" || (code != StatusCode::kUnavailable && code != StatusCode::kDeviceError)) return false;
  std::fprintf(stderr, "note: Vulkan failed (%s); running on the CPU\n", failure.message().c_str());
  return true;
}

int run(const SampleOptions& o) {
  // 1. The Vulkan device first, so a missing one fails before the asset is fitted.
  std::unique_ptr<vk::Gpu> gpu;
  if (o.backend != "cpu") {
    Result<vk::Gpu> opened = vk::Gpu::open(o.device, o.validation);
    if (opened.ok()) {
      gpu = std::make_unique<vk::Gpu>(std::move(opened).value());
    } else if (!fallsBackToCpu(o, opened.status())) {
      return fail(Status(opened.status().code(), "no Vulkan device opens: " + opened.status().message()));
    }
  }

  // 2. The asset, loaded once: a .odsk file, or the cat fitted now. Presets: its own materials and static.
  const auto load_start = std::chrono::steady_clock::now();
  // [runtime-snippet]
  Result<DeformAsset> source = o.asset.empty() ? fitCat(o.data) : loadAsset(o.asset);
  if (!source.ok()) return fail(source.status());
  RuntimeAssetOptions asset_options;
  asset_options.presets = {staticPreset()};
  Result<RuntimeAsset> asset = RuntimeAsset::create(*source, asset_options);
  if (!asset.ok()) return fail(asset.status());
  // [runtime-snippet]
  std::printf("asset: %s, %u vertices, %u bones, %u segments, %u presets (%s in %.2f s)\n",
              o.asset.empty() ? "cat-poses fitted" : o.asset.string().c_str(), asset->vertexCount(), asset->boneCount(),
              asset->segmentCount(), asset->presetCount(), o.asset.empty() ? "fitted" : "loaded", secondsSince(load_start));

  // 3. A runtime on the chosen backend, sized once for every instance.
  // [runtime-snippet]
  RuntimeOptions options;
  options.capacity = o.instances;
  options.threads = o.threads;
  std::unique_ptr<DeformRuntime> runtime;
  VulkanRuntime* vulkan = nullptr;
  if (gpu) {
    Result<VulkanRuntime> created = VulkanRuntime::create(gpu->device, *asset, options, {.bounds = readback(o.bounds)});
    if (created.ok()) {
      runtime = std::make_unique<VulkanRuntime>(std::move(created).value());
      vulkan = static_cast<VulkanRuntime*>(runtime.get());
    } else if (fallsBackToCpu(o, created.status())) {  // --backend auto: out of memory, device lost
      gpu.reset();
    } else {
      return fail(created.status());
    }
  }
  if (!gpu) {
    Result<CpuRuntime> created = CpuRuntime::create(*asset, options);
    if (!created.ok()) return fail(created.status());
    runtime = std::make_unique<CpuRuntime>(std::move(created).value());
  }
  // [runtime-snippet]
  std::optional<EngineSubmissions> engine;  // after the runtime, so it goes first and waits for its submissions
  if (o.record && vulkan != nullptr) {
    Result<EngineSubmissions> created = EngineSubmissions::create(gpu->device, *vulkan);
    if (!created.ok()) return fail(created.status());
    engine.emplace(std::move(created).value());
  }
  if (gpu) {
    std::printf("backend: vulkan on %s%s; bounds %s\n", gpu->device.name(),
                engine ? ", frames recorded into the sample's own command buffers" : "",
                vulkan->stagedBounds() ? "copied to cached host memory" : "read from their mapping");
  } else {
    std::printf("backend: cpu, %u threads\n", WorkerArena(o.threads).threads());
  }
  {
    const RuntimeMemory memory = runtime->memory();
    constexpr double kMiB = 1024.0 * 1024.0;
    std::printf("memory: %.2f MiB (asset %.2f, inputs %.2f, outputs %.2f for %u frames in flight; %.1f KiB per "
                "instance; %.2f MiB device-local)\n",
                static_cast<double>(memory.total()) / kMiB, static_cast<double>(memory.asset) / kMiB,
                static_cast<double>(memory.inputs) / kMiB, static_cast<double>(memory.outputs) / kMiB,
                runtime->framesInFlight(), memory.perInstance() / 1024.0, static_cast<double>(memory.device_local) / kMiB);
  }
  const std::uint64_t frame_count = static_cast<std::uint64_t>(std::llround(o.seconds * kHz));
  std::printf("animating %u instances x %u vertices for %.2f s at %.0f Hz (%llu frames)\n", o.instances,
              asset->vertexCount(), o.seconds, kHz, static_cast<unsigned long long>(frame_count));

  // 4. The frame loop.
  DeformRuntime& rt = *runtime;
  std::vector<gpu::BoneMatrix> bones(std::size_t{o.instances} * asset->boneCount());
  std::vector<InstanceBounds> bounds(o.instances);
  std::vector<double> set_seconds(rt.framesInFlight() + 1, 0.0);
  Totals totals;
  const auto loop_start = std::chrono::steady_clock::now();
  // [runtime-snippet]
  if (Status s = rt.setInstanceCount(o.instances); !s.ok()) return fail(s);
  for (std::uint64_t f = 0; f < frame_count; ++f) {
    const double now = static_cast<double>(f) / kHz;
    const auto set_start = std::chrono::steady_clock::now();
    for (std::uint32_t k = 0; k < o.instances; ++k) {
      std::span<gpu::BoneMatrix> own = std::span(bones).subspan(std::size_t{k} * asset->boneCount(), asset->boneCount());
      if (k % 4 == 3) engineBones(*asset, stateOf(*asset, k, now, {}).time, k, own);
      if (Status s = rt.setInstance(k, stateOf(*asset, k, now, own)); !s.ok()) return fail(s);
    }
    const double set_time = secondsSince(set_start);
    // Deforms every instance: one dispatch (after the fold, plus normals) on Vulkan; waits only for the frame
    // that used this slot two frames ago, so the GPU still runs the previous frame meanwhile. With
    // --record, the same commands go into the engine's command buffer, which it submits itself.
    Result<std::uint64_t> frame = engine ? engine->record() : rt.submitFrame();
    if (!frame.ok()) return fail(frame.status());
    if (vulkan != nullptr) {
      // A renderer binds this frame's buffers as vertex input after recording the barriers:
      //   barriers->record(cmd); vkCmdBindVertexBuffers(cmd, 0, 1, &buffers->positions, &offset_of_instance);
      Result<RuntimeFrameBuffers> buffers = vulkan->frameBuffers(*frame);
      Result<RuntimeOutputBarriers> barriers = vulkan->outputBarriers(*frame);
      if (!buffers.ok() || !barriers.ok()) return fail(buffers.ok() ? barriers.status() : buffers.status());
    }
    set_seconds[*frame % set_seconds.size()] = set_time;
    // The previous frame is done or nearly: its bounds cull the next frame's draws, its times are final.
    if (*frame > 1) {
      if (engine) {  // the engine's fence for it, and its word to the runtime
        if (Status s = engine->complete(*frame - 1); !s.ok()) return fail(s);
      }
      Result<FrameTimes> times = rt.frameTimes(*frame - 1);  // waits for the frame
      if (!times.ok()) return fail(times.status());
      const auto read_start = std::chrono::steady_clock::now();  // so this times the read alone
      if (Status s = rt.readBounds(*frame - 1, bounds); !s.ok()) return fail(s);
      totals.read_bounds += secondsSince(read_start);
      ++totals.bounds_reads;
      report(*times, *frame - 1, set_seconds[(*frame - 1) % set_seconds.size()], vulkan != nullptr, o.quiet, totals);
    }
  }
  // [runtime-snippet]
  if (engine && rt.lastFrame() > 0) {
    if (Status s = engine->complete(rt.lastFrame()); !s.ok()) return fail(s);
  }
  if (Status s = rt.wait(); !s.ok()) return fail(s);
  const std::uint64_t last = rt.lastFrame();
  if (last > 0) {
    Result<FrameTimes> times = rt.frameTimes(last);
    if (!times.ok()) return fail(times.status());
    report(*times, last, set_seconds[last % set_seconds.size()], vulkan != nullptr, o.quiet, totals);
    if (Status s = rt.readBounds(last, bounds); !s.ok()) return fail(s);
  }
  const double wall = secondsSince(loop_start);

  // 5. Totals, the scene's box from the per-instance boxes, and the self-check.
  if (totals.frames > 0) {
    const double n = static_cast<double>(totals.frames);
    const double vertices = static_cast<double>(o.instances) * asset->vertexCount();
    std::printf("totals: %llu frames in %.2f s wall; per frame: host %.3f ms (worst %.3f, prepare %.3f, read bounds "
                "%.3f), %s %.3f ms (worst %.3f); %.1f M vertices/s deformed\n",
                static_cast<unsigned long long>(totals.frames), wall, 1e3 * totals.host / n, 1e3 * totals.worst_host,
                1e3 * totals.prepare / n, 1e3 * totals.read_bounds / static_cast<double>(std::max<std::uint64_t>(totals.bounds_reads, 1)), vulkan ? "gpu" : "cpu deform", 1e3 * totals.deform / n,
                1e3 * totals.worst_deform, totals.deform > 0.0 ? vertices * n / totals.deform * 1e-6 : 0.0);
    InstanceBounds scene;
    for (const InstanceBounds& b : bounds) {
      scene.min = glm::min(scene.min, b.min);
      scene.max = glm::max(scene.max, b.max);
    }
    std::printf("scene box (last frame): (%.2f, %.2f, %.2f) - (%.2f, %.2f, %.2f)\n", scene.min.x, scene.min.y,
                scene.min.z, scene.max.x, scene.max.y, scene.max.z);
    const double last_time = static_cast<double>(last - 1) / kHz;
    // Instance 0, and one whose time and bones differ from it (the fourth, or the last of fewer).
    std::vector<std::uint32_t> checked{0u};
    if (o.instances > 1) checked.push_back(std::min<std::uint32_t>(3u, o.instances - 1));
    for (std::uint32_t k : checked) {
      std::span<gpu::BoneMatrix> own = std::span(bones).subspan(std::size_t{k} * asset->boneCount(), asset->boneCount());
      Result<double> error = checkInstance(rt, last, k, last_time, own);
      if (!error.ok()) return fail(error.status());
      std::printf("check: instance %u vs the double-precision reference: %.2e of the box (limit %.0e)\n", k, *error,
                  kCheckTolerance);
      if (!(*error <= kCheckTolerance)) return fail(internalError("instance " + std::to_string(k) + " is off the reference"));
    }
  }
  if (gpu && gpu->instance.validationEnabled() && gpu->instance.debugLog().count() > 0) {
    return fail(internalError("the Vulkan validation layer reported " + std::to_string(gpu->instance.debugLog().count()) +
                              " message(s); first: " + gpu->instance.debugLog().messages().front()));
  }
  return 0;
}

}  // namespace
}  // namespace odeskin

namespace {

int parseAndRun(int argc, char** argv) {
  odeskin::SampleOptions o;
  CLI::App app("odeskin_runtime_sample: many instances of one asset deformed every frame, with timings");
  app.add_option("asset", o.asset, "A .odsk asset (default: fit the cat from --data/cat-poses)");
  app.add_option("--backend", o.backend, "cpu, vulkan, or auto (Vulkan where a device opens, else the CPU)")
      ->check(CLI::IsMember({"cpu", "vulkan", "auto"}));
  app.add_option("--instances", o.instances, "Instances animated every frame")->check(CLI::Range(1u, 1u << 20));
  // CLI::Range lets NaN through (every comparison with it is false), and a NaN --seconds then
  // played frames forever.
  const CLI::Validator finite(
      [](const std::string& text) {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        return end != text.c_str() && *end == '\0' && std::isfinite(x) ? std::string()
                                                                        : "Value " + text + " is not a finite number";
      },
      "FINITE");
  app.add_option("--seconds", o.seconds, "Simulated seconds at 60 Hz")->check(finite)->check(CLI::Range(1.0 / 60.0, 3600.0));
  app.add_option("--data", o.data, "The shared data folder (holds cat-poses/)");
  app.add_option("--device", o.device, "Vulkan device: auto, an index, or a name substring");
  app.add_flag("--validation", o.validation, "Khronos validation layer; any message fails the run");
  app.add_option("--threads", o.threads, "Host threads (0: all)");
  app.add_flag("-q,--quiet", o.quiet, "Totals only, no per-frame lines");
  app.add_flag("--record", o.record,
               "Vulkan: record each frame into the sample's own command buffers and submit them, as an engine "
               "does with its draws (VulkanRuntime::recordFrame), instead of the runtime submitting");
  app.add_option("--bounds", o.bounds,
                 "Vulkan: how the host reads each frame's boxes: auto (mapped where that memory is cached for the "
                 "host, else staged), mapped (the GPU's buffer itself), staged (copied into cached host memory)")
      ->check(CLI::IsMember({"auto", "mapped", "staged"}));
  odeskin::requireDecimalIntegers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  // --record and --bounds name Vulkan objects; under auto they could silently mean nothing.
  if (o.record && o.backend != "vulkan") {
    std::fprintf(stderr, "odeskin_runtime_sample: --record needs --backend vulkan\n");
    return 2;
  }
  if (o.bounds != "auto" && o.backend != "vulkan") {
    std::fprintf(stderr, "odeskin_runtime_sample: --bounds needs --backend vulkan\n");
    return 2;
  }
  // The CPU backend opens no device: these options would change nothing.
  if (o.backend == "cpu" && (o.validation || o.device != "auto")) {
    std::fprintf(stderr, "odeskin_runtime_sample: %s needs --backend vulkan or auto\n",
                 o.validation ? "--validation" : "--device");
    return 2;
  }
  if (const unsigned usable = odeskin::usableThreads(o.threads); o.threads > usable) {
    std::fprintf(stderr, "note: --threads %u: this machine runs at most %u, so the sample uses %u\n", o.threads, usable,
                 usable);
  }
  return odeskin::run(o);
}

}  // namespace

// A failure to allocate (1,000 instances of a big asset) or a library's exception ends the sample
// with one line and status 1, not an abort.
int main(int argc, char** argv) {
  int code = 1;
  try {
    code = parseAndRun(argc, argv);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "odeskin_runtime_sample: error: out of memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "odeskin_runtime_sample: error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "odeskin_runtime_sample: error: an unknown exception\n");
  }
  return odeskin::checkStandardOutput("odeskin_runtime_sample: error: ", "", code);
}
