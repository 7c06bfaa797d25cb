// SPDX-License-Identifier: MIT
#include "demo.hpp"
#include "file_extension.hpp"
#include "output_paths.hpp"

#include <chrono>
#include <cstdio>
#include <optional>
#include <ostream>

#include "engine/io/asset_file.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "engine/core/thread_count.hpp"
#include "host/gpu_deformer.hpp"

namespace odeskin {
namespace {

using Clock = std::chrono::steady_clock;

// Key poses reproduced to 1e-6 of the box, well inside the 1e-5 the demo promises for its ends.
constexpr double kDemoKeyTolerance = 1e-6;

Result<Material> namedMaterial(const std::string& name) {
  if (name == "skin") return skinMaterial();
  if (name == "static") return staticMaterial();
  return invalidArgument("unknown material '" + name + "' (expected skin or static)");
}

double maxError(std::span<const Vec3> a, std::span<const Vec3> b, double box) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, glm::length(a[i] - b[i]));
  return worst / box;
}

std::vector<Vec3> toVec3(std::span<const gpu::Float4> in) {
  std::vector<Vec3> out(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) out[i] = Vec3(in[i].x, in[i].y, in[i].z);
  return out;
}

// Opens Vulkan for kVulkan (required) or kAuto (optional: nullopt means "use the CPU").
Result<std::optional<vk::Gpu>> openGpu(const DemoOptions& options, std::ostream& log) {
  if (options.backend == Backend::kCpu) {
    if (options.validation) log << "note: --validation checks Vulkan calls, and --backend cpu makes none\n";
    return std::optional<vk::Gpu>{};
  }
  Result<vk::Gpu> gpu = vk::Gpu::open(options.device, options.validation);
  if (gpu.ok()) return std::optional<vk::Gpu>(std::move(gpu).value());
  if (options.backend == Backend::kVulkan) return gpu.status();
  log << "note: Vulkan failed (" << gpu.status().message() << "); using the CPU backend\n";
  return std::optional<vk::Gpu>{};
}

Status writeOutputs(const DemoOptions& options, const FaceList& faces, const DemoResult& result) {
  if (options.output_dir.empty()) return okStatus();
  std::error_code ec;
  std::filesystem::create_directories(options.output_dir, ec);
  if (ec) return ioError(options.output_dir.string() + ": cannot create directory: " + ec.message());
  ODESKIN_TRY(writeObj(options.output_dir / "start.obj", result.start_positions, faces, "odeskin demo: pose 0"));
  ODESKIN_TRY(writeObj(options.output_dir / "end.obj", result.end_positions, faces, "odeskin demo: pose 1"));
  for (std::size_t f = 0; f < result.frames.size(); ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04zu.obj", f);
    ODESKIN_TRY(writeObj(options.output_dir / name, result.frames[f], faces, "odeskin demo frame"));
  }
  return okStatus();
}

}  // namespace

Result<DemoResult> runDemo(const DemoOptions& options, std::ostream& log) {
  if (options.frames < 2) return invalidArgument("--frames must be at least 2, got " + std::to_string(options.frames));
  if (!options.asset_path.empty() && lowerExtension(options.asset_path) != ".odsk") {
    return invalidArgument("--save-asset " + options.asset_path.string() + ": the asset is written as .odsk");
  }
  ODESKIN_ASSIGN_OR_RETURN(Material material, namedMaterial(options.material));
  ODESKIN_ASSIGN_OR_RETURN(ProceduralArm arm, makeProceduralArm(ArmOptions{}));

  FitOptions fit;
  fit.modes = options.modes;
  fit.residual_space = options.residual_space;
  fit.materials = {material};
  fit.key_tolerance = kDemoKeyTolerance;
  FitReport report;
  ODESKIN_ASSIGN_OR_RETURN(DeformAsset asset, fitDeformAsset(arm.fit_input, fit, &report));
  if (!options.asset_path.empty()) {
    ODESKIN_TRY(createParentFolder(options.asset_path));
    ODESKIN_TRY(saveAsset(options.asset_path, asset));
    log << "asset: " << options.asset_path.string() << "\n";
  }
  ODESKIN_ASSIGN_OR_RETURN(DeformPlayer player, DeformPlayer::create(asset));
  ODESKIN_ASSIGN_OR_RETURN(PackedDeformData packed, packDeformAsset(asset));
  log << "arm: " << asset.vertexCount() << " vertices, " << asset.curveCount() << " curves, N = " << asset.modes
      << ", material " << options.material << " (" << describe(material) << "), " << report.remainder_count
      << " sparse remainders, " << packed.byteSize() << " GPU bytes\n";

  ODESKIN_ASSIGN_OR_RETURN(std::optional<vk::Gpu> gpu, openGpu(options, log));
  std::optional<GpuDeformer> deformer;
  DemoResult result;
  // kAuto: a Vulkan failure after the device opened (out of memory, device lost) also means the CPU.
  auto fallBack = [&](const Status& why) {
    deformer.reset();
    gpu.reset();
    log << "note: Vulkan failed (" << why.message() << "); using the CPU backend\n";
  };
  if (gpu) {
    Result<GpuDeformer> created = GpuDeformer::create(gpu->device, packed);
    if (created.ok()) {
      deformer.emplace(std::move(created).value());
      result.device = std::string("vulkan: ") + gpu->device.name();
    } else if (options.backend == Backend::kVulkan) {
      return created.status();
    } else {
      fallBack(created.status());
    }
  }
  const unsigned threads = usableThreads(options.threads);  // what the fast job runs
  const std::string cpu_device = "cpu: fast path, " + std::to_string(threads) + " thread" + (threads == 1 ? "" : "s");
  if (!deformer) result.device = cpu_device;
  log << "device: " << result.device << "\n";

  std::vector<ModeBasisValue> basis(player.basisSize());
  std::vector<BoneTransform> bones(asset.bone_count);
  std::vector<gpu::ModeBasis> gpu_basis(basis.size());
  std::vector<gpu::BoneMatrix> gpu_bones(bones.size());
  std::vector<gpu::Float4> out(asset.vertexCount());
  double wall = 0.0;
  double gpu_time = 0.0;
  for (int f = 0; f < options.frames; ++f) {
    const double t = static_cast<double>(f) / (options.frames - 1);
    const auto [segment, tau] = player.locate(t);
    const Clock::time_point start = Clock::now();
    player.basisAt(tau, basis);
    player.bonesAt(asset, segment, tau, bones);
    toGpuBasis(basis, gpu_basis);
    toGpuBones(bones, gpu_bones);
    if (deformer) {
      Status ran = deformer->run(GpuDeformFrame{segment, gpu_bones, gpu_basis});
      wall += std::chrono::duration<double>(Clock::now() - start).count();
      if (ran.ok()) {
        gpu_time += deformer->lastGpuSeconds();
        ran = deformer->readPositions(out);
      }
      if (!ran.ok()) {
        if (options.backend == Backend::kVulkan) return ran;
        fallBack(ran);
        result.device = cpu_device;
        ODESKIN_TRY((FourierDeformFastJob{&packed, segment, gpu_bones, gpu_basis, out, options.threads}).run());
      }
    } else {
      ODESKIN_TRY((FourierDeformFastJob{&packed, segment, gpu_bones, gpu_basis, out, options.threads}).run());
      wall += std::chrono::duration<double>(Clock::now() - start).count();
    }
    result.frames.push_back(toVec3(out));
  }
  if (gpu && gpu->instance.validationEnabled() && gpu->instance.debugLog().count() > 0) {
    return internalError("the Vulkan validation layer reported " + std::to_string(gpu->instance.debugLog().count()) +
                         " message(s); first: " + gpu->instance.debugLog().messages().front());
  }
  result.mean_frame_seconds = wall / options.frames;
  result.mean_gpu_seconds = gpu_time / options.frames;
  result.start_positions = arm.start_positions;
  result.end_positions = arm.end_positions;
  result.box_side = longestBoxSide(arm.end_positions);
  result.first_frame_error = maxError(result.frames.front(), result.start_positions, result.box_side);
  result.last_frame_error = maxError(result.frames.back(), result.end_positions, result.box_side);
  ODESKIN_TRY(writeOutputs(options, asset.faces, result));
  return result;
}

}  // namespace odeskin
