// SPDX-License-Identifier: MIT
#include "libigl_io.hpp"
#include "obj_reader.hpp"

namespace odeskin {

Result<ExampleSet> readLibiglExamples(const std::filesystem::path& rest, std::span<const std::filesystem::path> poses,
                                      const std::filesystem::path& tgf, const std::filesystem::path* weights,
                                      std::span<const std::filesystem::path> transforms) {
  ODESKIN_ASSIGN_OR_RETURN(ExampleSet examples, readObjSequence(poses, &rest));
  ODESKIN_ASSIGN_OR_RETURN(Skeleton skeleton, readTgf(tgf));
  Rig rig;
  rig.skeleton = std::move(skeleton);
  const std::size_t bones = rig.skeleton.boneCount();
  if (weights) {
    ODESKIN_ASSIGN_OR_RETURN(rig.influences, readWeightsDmat(*weights, examples.rest_positions.size(), bones));
  }
  if (!transforms.empty()) {
    if (transforms.size() != poses.size()) {
      return invalidArgument(std::to_string(transforms.size()) + " transform files for " + std::to_string(poses.size()) +
                             " poses: give one .Tmat per pose, in the same order");
    }
    for (const std::filesystem::path& path : transforms) {
      ODESKIN_ASSIGN_OR_RETURN(std::vector<RigidTransform> key, readTmat(path, bones));
      rig.key_poses.push_back(std::move(key));
    }
  }
  ODESKIN_TRY(validateRig(rig, examples.rest_positions.size(), examples.poses.size()));
  examples.rig = std::move(rig);
  return examples;
}

}  // namespace odeskin
