// SPDX-License-Identifier: MIT
#include "bench_assets.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <span>
#include <string>

#include "engine/io/obj_reader.hpp"
#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/kernels/lbs_job.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "engine/offline/residual_fit.hpp"
#include "engine/pipeline/fit_pipeline.hpp"

namespace odeskin::bench {
namespace {

struct GpuState {
  bool tried = false;
  std::optional<vk::Gpu> gpu;
  std::string note;
};

GpuState& gpuState() {
  static GpuState state;
  return state;
}

std::unique_ptr<BenchAsset>& cachedAsset() {
  static std::unique_ptr<BenchAsset> asset;
  return asset;
}

std::vector<VerifiedSize>& verifiedList() {
  static std::vector<VerifiedSize> list;
  return list;
}

// Setup failures are not benchmark results: stop the whole program with the reason.
[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "odeskin_deform_bench: %s\n", what.c_str());
  std::fflush(nullptr);
  std::_Exit(3);  // not exit(): a benchmark thread may still be running, and exit() is not thread-safe
}

template <typename T>
T orFail(Result<T> result, const char* what) {
  if (!result.ok()) fail(std::string(what) + ": " + result.status().toString());
  return std::move(result).value();
}

void orFail(const Status& status, const char* what) {
  if (!status.ok()) fail(std::string(what) + ": " + status.toString());
}

// Worst |a_i - b_i| / box over all vertices; exits naming the vertex when above kVerifyTolerance.
double verify(std::span<const Vec3> expected, std::span<const gpu::Float4> actual, double box, const char* what,
              std::uint32_t vertex_count, int modes) {
  double worst = 0.0;
  std::size_t worst_index = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const Vec3 a(actual[i].x, actual[i].y, actual[i].z);
    double e = glm::length(a - expected[i]);
    if (std::isnan(e)) e = INFINITY;  // a NaN output must fail, and NaN compares false
    if (e > worst) {
      worst = e;
      worst_index = i;
    }
  }
  const double relative = worst / box;
  if (!(relative <= kVerifyTolerance)) {
    const Vec3& x = expected[worst_index];
    const gpu::Float4& y = actual[worst_index];
    char message[512];
    std::snprintf(message, sizeof message,
                  "verification failed for %s at V = %u, N = %d: vertex %zu expected (%.9g, %.9g, %.9g) got "
                  "(%.9g, %.9g, %.9g), error %.3g of the box side (limit %.1g)",
                  what, vertex_count, modes, worst_index, x.x, x.y, x.z, static_cast<double>(y.x),
                  static_cast<double>(y.y), static_cast<double>(y.z), relative, kVerifyTolerance);
    fail(message);
  }
  return relative;
}

std::string& catDirectory() {
  static std::string dir;
  return dir;
}

// cat-00 (rest) to cat-09 through the whole fitting pipeline (automatic rig), skin material.
DeformAsset fitCat(int modes) {
  std::vector<std::filesystem::path> poses;
  for (int k = 0; k < 10; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "cat-%02d.obj", k);
    poses.push_back(std::filesystem::path(catDirectory()) / name);
  }
  const ExampleSet examples = orFail(readObjSequence(poses), "readObjSequence (cat-poses)");
  PipelineOptions options;
  options.modes = modes;
  options.material = skinMaterial();
  return orFail(runFitPipeline(examples, options), "runFitPipeline (cat-poses)").asset;
}

DeformAsset fitArm(std::uint32_t nominal_vertices, int modes) {
  ArmOptions arm_options;
  arm_options.ring_vertices = kRingVertices;
  arm_options.rings = std::max<std::uint32_t>(3, static_cast<std::uint32_t>(std::lround(
                                                     static_cast<double>(nominal_vertices) / kRingVertices)));
  ProceduralArm arm = orFail(makeProceduralArm(arm_options), "makeProceduralArm");
  FitOptions fit;
  fit.modes = modes;
  fit.materials = {skinMaterial()};
  return orFail(fitDeformAsset(arm.fit_input, fit), "fitDeformAsset");
}

// Fit, pack and set up the middle frame of the animation (t = 0.5 of the first segment).
std::unique_ptr<BenchAsset> buildAsset(std::uint32_t nominal_vertices, int modes) {
  auto b = std::make_unique<BenchAsset>();
  b->modes = modes;
  b->asset = nominal_vertices == kCatVertices ? fitCat(modes) : fitArm(nominal_vertices, modes);
  b->vertex_count = static_cast<std::uint32_t>(b->asset.vertexCount());
  b->packed = orFail(packDeformAsset(b->asset), "packDeformAsset");
  const DeformPlayer player = orFail(DeformPlayer::create(b->asset), "DeformPlayer::create");
  const auto [segment, tau] = player.locate(0.5 * player.segmentCount());
  b->segment = segment;
  b->basis.resize(player.basisSize());
  b->bones.resize(b->asset.bone_count);
  player.basisAt(tau, b->basis);
  player.bonesAt(b->asset, segment, tau, b->bones);
  b->gpu_basis.resize(b->basis.size());
  b->gpu_bones.resize(b->bones.size());
  toGpuBasis(b->basis, b->gpu_basis);
  toGpuBones(b->bones, b->gpu_bones);
  b->kernel.emplace(orFail(CpuDeformKernel::create(b->packed), "CpuDeformKernel::create"));
  if (const vk::Device* device = benchDevice()) {
    b->gpu_deformer.emplace(orFail(GpuDeformer::create(*device, b->packed), "GpuDeformer::create"));
    b->gpu_lbs.emplace(orFail(GpuLbs::create(*device, b->packed), "GpuLbs::create"));
  }
  return b;
}

// One frame of every backend against the double reference, for both kernels.
void verifyAsset(BenchAsset& b) {
  const std::uint32_t v = b.vertex_count;
  std::vector<Vec3> expected(v);
  orFail(referenceJob(b.asset, b.segment, b.basis, b.bones, expected).run(), "reference job");
  const double box = longestBoxSide(expected);
  std::vector<gpu::Float4> actual(v);
  for (unsigned threads : {1u, 0u}) {
    std::fill(actual.begin(), actual.end(), gpu::Float4{});
    orFail(FourierDeformFastJob{&b.packed, b.segment, b.gpu_bones, b.gpu_basis, actual, threads}.run(), "fast job");
    b.fast_error = std::max(b.fast_error, verify(expected, actual, box, "cpu_fast", v, b.modes));
  }
  for (unsigned threads : {1u, 0u}) {
    std::fill(actual.begin(), actual.end(), gpu::Float4{});
    orFail(b.kernel->deform(b.segment, b.gpu_bones, b.gpu_basis, actual, threads), "CpuDeformKernel::deform");
    b.kernel_error = std::max(b.kernel_error, verify(expected, actual, box, "cpu_kernel", v, b.modes));
  }
  if (b.gpu_deformer) {
    std::fill(actual.begin(), actual.end(), gpu::Float4{});
    orFail(b.gpu_deformer->run(GpuDeformFrame{b.segment, b.gpu_bones, b.gpu_basis}), "GpuDeformer::run");
    orFail(b.gpu_deformer->readPositions(actual), "GpuDeformer::readPositions");
    b.gpu_error = verify(expected, actual, box, "vulkan", v, b.modes);
  }
  orFail(LbsJob{b.asset.rest_positions, b.asset.influences, b.bones, expected}.run(), "LBS reference job");
  for (unsigned threads : {1u, 0u}) {
    std::fill(actual.begin(), actual.end(), gpu::Float4{});
    orFail(LbsFastJob{&b.packed, b.gpu_bones, actual, threads}.run(), "LBS fast job");
    b.lbs_fast_error = std::max(b.lbs_fast_error, verify(expected, actual, box, "lbs cpu_fast", v, b.modes));
  }
  for (unsigned threads : {1u, 0u}) {
    std::fill(actual.begin(), actual.end(), gpu::Float4{});
    orFail(b.kernel->skin(b.gpu_bones, actual, threads), "CpuDeformKernel::skin");
    b.lbs_kernel_error = std::max(b.lbs_kernel_error, verify(expected, actual, box, "lbs cpu_kernel", v, b.modes));
  }
  if (b.gpu_lbs) {
    std::fill(actual.begin(), actual.end(), gpu::Float4{});
    orFail(b.gpu_lbs->run(GpuLbsFrame{b.gpu_bones}), "GpuLbs::run");
    orFail(b.gpu_lbs->readPositions(actual), "GpuLbs::readPositions");
    b.lbs_gpu_error = verify(expected, actual, box, "lbs vulkan", v, b.modes);
  }
}

}  // namespace

const vk::Device* benchDevice() {
  GpuState& s = gpuState();
  if (!s.tried) {
    s.tried = true;
    Result<vk::Gpu> gpu = vk::Gpu::open("auto", false);
    if (gpu.ok()) {
      s.gpu.emplace(std::move(gpu).value());
      s.note = s.gpu->device.name();
    } else {
      s.note = "none (" + gpu.status().toString() + ")";
    }
  }
  return s.gpu ? &s.gpu->device : nullptr;
}

const std::string& benchDeviceNote() {
  benchDevice();
  return gpuState().note;
}

BenchAsset& benchAsset(std::uint32_t vertex_count, int modes) {
  std::unique_ptr<BenchAsset>& cached = cachedAsset();
  static std::uint32_t cached_nominal = 0;
  if (cached && cached_nominal == vertex_count && cached->modes == modes) return *cached;
  cached.reset();  // free the previous size (and its GPU buffers) before building the next
  const auto start = std::chrono::steady_clock::now();
  cached = buildAsset(vertex_count, modes);
  cached_nominal = vertex_count;
  verifyAsset(*cached);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  verifiedList().push_back(VerifiedSize{cached->vertex_count, modes, cached->fast_error, cached->gpu_error,
                                        cached->lbs_fast_error, cached->lbs_gpu_error, cached->kernel_error,
                                        cached->lbs_kernel_error, cached->kernel->stats(), cached->kernel->arch(),
                                        seconds});
  return *cached;
}

const std::vector<VerifiedSize>& verifiedSizes() { return verifiedList(); }

void setCatDirectory(std::string dir) { catDirectory() = std::move(dir); }
bool hasCatDirectory() { return !catDirectory().empty(); }

void releaseAll() {
  cachedAsset().reset();
  gpuState().gpu.reset();
}

}  // namespace odeskin::bench
