// SPDX-License-Identifier: MIT
// What an engine that links odeskin::engine and odeskin::runtime does first: fit an asset (here the
// procedural arm, so no file is needed), load it into the runtime, deform instances on the CPU
// backend and check one against the double-precision reference. Built with odeskin::vulkan_runtime,
// it also deforms the same frame on the first Vulkan device and checks it against the CPU's.
// Exit 0 and "ok" lines, else 1.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/offline/deform_player.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "engine/offline/residual_fit.hpp"
#include "engine/runtime/cpu_runtime.hpp"
#include "engine/runtime/runtime_asset.hpp"
#if defined(ODESKIN_CONSUMER_VULKAN)
#include "host/device.hpp"
#include "host/runtime/vulkan_runtime.hpp"
#endif

namespace {

int fail(const odeskin::Status& status) {
  std::fprintf(stderr, "odeskin_consumer: %s\n", status.toString().c_str());
  return 1;
}

#if defined(ODESKIN_CONSUMER_VULKAN)
// Instance 1 at `time` on the Vulkan runtime, against the CPU runtime's `expected` (both float32).
int checkVulkan(const odeskin::RuntimeAsset& asset, double time, const std::vector<odeskin::gpu::Float4>& expected,
                double size) {
  using namespace odeskin;
  Result<vk::Gpu> gpu = vk::Gpu::open();
  if (!gpu.ok()) return fail(gpu.status());
  RuntimeOptions options;
  options.capacity = 3;
  Result<VulkanRuntime> runtime = VulkanRuntime::create(gpu->device, asset, options);
  if (!runtime.ok()) return fail(runtime.status());
  if (Status s = runtime->setInstanceCount(3); !s.ok()) return fail(s);
  if (Status s = runtime->setInstance(1, InstanceState::atTime(time)); !s.ok()) return fail(s);
  Result<std::uint64_t> frame = runtime->submitFrame();
  if (!frame.ok()) return fail(frame.status());
  std::vector<gpu::Float4> positions(expected.size());
  if (Status s = runtime->readPositions(*frame, 1, positions); !s.ok()) return fail(s);
  double gap = 0.0;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    gap = std::max(gap, glm::length(glm::dvec3(positions[i].x - expected[i].x, positions[i].y - expected[i].y,
                                               positions[i].z - expected[i].z)));
  }
  if (!(gap <= 1e-5 * size)) {
    std::fprintf(stderr, "odeskin_consumer: on %s, instance 1 differs from the CPU runtime by %.3g of the size\n",
                 gpu->device.name(), gap / size);
    return 1;
  }
  std::printf("odeskin_consumer: ok: the same frame on %s, %.2g of the size from the CPU runtime\n", gpu->device.name(),
              gap / size);
  return 0;
}
#endif

}  // namespace

int main() {
  using namespace odeskin;
  Result<ProceduralArm> arm = makeProceduralArm(ArmOptions{});
  if (!arm.ok()) return fail(arm.status());
  FitOptions fit;
  fit.materials = {skinMaterial()};
  Result<DeformAsset> asset = fitDeformAsset(arm->fit_input, fit);
  if (!asset.ok()) return fail(asset.status());

  Result<RuntimeAsset> runtime_asset = RuntimeAsset::create(*asset);
  if (!runtime_asset.ok()) return fail(runtime_asset.status());
  RuntimeOptions options;
  options.capacity = 3;
  Result<CpuRuntime> runtime = CpuRuntime::create(*runtime_asset, options);
  if (!runtime.ok()) return fail(runtime.status());
  if (Status s = runtime->setInstanceCount(3); !s.ok()) return fail(s);
  constexpr double kTime = 0.5;
  if (Status s = runtime->setInstance(1, InstanceState::atTime(kTime)); !s.ok()) return fail(s);
  Result<std::uint64_t> frame = runtime->submitFrame();
  if (!frame.ok()) return fail(frame.status());
  std::vector<gpu::Float4> positions(asset->vertexCount());
  if (Status s = runtime->readPositions(*frame, 1, positions); !s.ok()) return fail(s);

  Result<DeformPlayer> player = DeformPlayer::create(*asset);
  if (!player.ok()) return fail(player.status());
  const auto [segment, tau] = player->locate(kTime);
  std::vector<Vec3> reference(asset->vertexCount());
  if (Status s = player->play(*asset, segment, tau, reference); !s.ok()) return fail(s);
  double gap = 0.0, size = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const Vec3 p(positions[i].x, positions[i].y, positions[i].z);
    gap = std::max(gap, glm::length(p - reference[i]));
    size = std::max(size, glm::length(reference[i] - reference[0]));
  }
  // float32 runtime against the double reference, as the runtime tests hold it.
  if (!(gap <= 1e-5 * size)) {
    std::fprintf(stderr, "odeskin_consumer: instance 1 differs from the reference by %.3g (%.3g of the size)\n", gap,
                 gap / size);
    return 1;
  }
  std::printf("odeskin_consumer: ok: %zu vertices, 3 instances on the CPU runtime, %.2g of the size from the "
              "reference\n",
              positions.size(), gap / size);
#if defined(ODESKIN_CONSUMER_VULKAN)
  return checkVulkan(*runtime_asset, kTime, positions, size);
#else
  return 0;
#endif
}
