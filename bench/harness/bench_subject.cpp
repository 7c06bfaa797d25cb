// SPDX-License-Identifier: MIT
#include "bench_subject.hpp"

#include "engine/offline/deform_player.hpp"
#include "tiled_asset.hpp"

namespace odeskin::bench {

Result<BenchFrame> benchFrame(const DeformAsset& asset, double t) {
  ODESKIN_ASSIGN_OR_RETURN(const DeformPlayer player, DeformPlayer::create(asset));
  const auto [segment, tau] = player.locate(t);
  BenchFrame frame;
  frame.segment = segment;
  frame.basis.resize(player.basisSize());
  frame.bones.resize(asset.bone_count);
  player.basisAt(tau, frame.basis);
  player.bonesAt(asset, segment, tau, frame.bones);
  frame.gpu_basis.resize(frame.basis.size());
  frame.gpu_bones.resize(frame.bones.size());
  toGpuBasis(frame.basis, frame.gpu_basis);
  toGpuBones(frame.bones, frame.gpu_bones);
  return frame;
}

Result<BenchSubject> makeSubject(const DeformAsset& source, std::size_t vertex_count, SkinningMode skinning, double t) {
  BenchSubject s;
  ODESKIN_ASSIGN_OR_RETURN(s.asset, tileDeformAsset(source, vertex_count));
  s.asset.skinning = skinning;
  ODESKIN_ASSIGN_OR_RETURN(s.packed, packDeformAsset(s.asset));
  ODESKIN_ASSIGN_OR_RETURN(s.frame, benchFrame(s.asset, t));
  return s;
}

}  // namespace odeskin::bench
