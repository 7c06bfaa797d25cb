// SPDX-License-Identifier: MIT
#include "asset_playback.hpp"

#include <ostream>

#include "host/gpu_deformer.hpp"

namespace odeskin {

AssetPlayback::AssetPlayback(AssetPlayback&&) noexcept = default;
AssetPlayback& AssetPlayback::operator=(AssetPlayback&&) noexcept = default;
AssetPlayback::~AssetPlayback() = default;

Result<AssetPlayback> AssetPlayback::create(const DeformAsset& asset, const PlaybackOptions& options,
                                            std::ostream* notes) {
  AssetPlayback playback;
  playback.asset_ = &asset;
  ODESKIN_ASSIGN_OR_RETURN(DeformPlayer player, DeformPlayer::create(asset));
  playback.player_.emplace(std::move(player));
  playback.basis_.resize(playback.player_->basisSize());
  playback.bones_.resize(asset.bone_count);
  playback.device_ = "cpu: double-precision reference";
  if (options.backend == Backend::kCpu) return playback;

  Result<vk::Gpu> gpu = vk::Gpu::open(options.device, options.validation);
  if (!gpu.ok()) {
    if (options.backend == Backend::kVulkan) return gpu.status();
    if (notes) *notes << "note: no usable Vulkan device (" << gpu.status().message() << "); playing on the CPU\n";
    return playback;
  }
  playback.gpu_ = std::make_unique<vk::Gpu>(std::move(gpu).value());
  ODESKIN_ASSIGN_OR_RETURN(PackedDeformData packed, packDeformAsset(asset));
  ODESKIN_ASSIGN_OR_RETURN(GpuDeformer deformer, GpuDeformer::create(playback.gpu_->device, packed));
  playback.deformer_ = std::make_unique<GpuDeformer>(std::move(deformer));
  playback.device_ = std::string("vulkan: ") + playback.gpu_->device.name();
  playback.gpu_basis_.resize(playback.basis_.size());
  playback.gpu_bones_.resize(playback.bones_.size());
  playback.gpu_out_.resize(asset.vertexCount());
  return playback;
}

Status AssetPlayback::positionsAt(double t, std::vector<Vec3>& out) {
  const auto [segment, tau] = player_->locate(t);
  player_->basisAt(tau, basis_);
  player_->bonesAt(*asset_, segment, tau, bones_);
  out.resize(asset_->vertexCount());
  if (!deformer_) return referenceJob(*asset_, segment, basis_, bones_, out).run();
  toGpuBasis(basis_, gpu_basis_);
  toGpuBones(bones_, gpu_bones_);
  ODESKIN_TRY(deformer_->run(GpuDeformFrame{segment, gpu_bones_, gpu_basis_}));
  ODESKIN_TRY(deformer_->readPositions(gpu_out_));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = Vec3(gpu_out_[i].x, gpu_out_[i].y, gpu_out_[i].z);
  return okStatus();
}

Status AssetPlayback::checkValidation() const {
  if (!gpu_ || !gpu_->instance.validationEnabled() || gpu_->instance.debugLog().count() == 0) return okStatus();
  return internalError("the Vulkan validation layer reported " + std::to_string(gpu_->instance.debugLog().count()) +
                       " message(s); first: " + gpu_->instance.debugLog().messages().front());
}

}  // namespace odeskin
