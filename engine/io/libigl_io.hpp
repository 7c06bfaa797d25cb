// SPDX-License-Identifier: MIT
// The libigl text formats of ../shared/data (its README, "File formats"): .tgf skeletons, .dmat
// dense matrices (skinning weights), .Tmat per-pose absolute bone transforms, and the viewer .json
// that stores a pose as relative bone rotations (forward kinematics gives the .Tmat).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "../core/result.hpp"
#include "../rig/rig.hpp"
#include "example_set.hpp"

namespace odeskin {

// Bone b is the b-th edge line; heads/tails are its start/end joints; the parent of b is the bone
// whose end joint is b's start joint (libigl directed_edge_parents). Names are "bone<b>".
// Joint lines must be numbered 1, 2, ... in order; columns past x y z (joints) or past the two
// joints (edges) are ignored, as is anything after the closing '#', which may be missing.
// kIoError / kParseError naming path and line: a malformed line, a bone joint out of range or
// starting where it ends, a joint ending two bones (ambiguous parent), a cycle, no bones.
Result<Skeleton> readTgf(const std::filesystem::path& path);
// readTgf on text already in memory; `source` stands for the path in the messages.
Result<Skeleton> parseTgf(const std::string& text, const std::string& source);

struct DenseMatrix {
  std::size_t rows = 0;
  std::size_t cols = 0;
  std::vector<double> values;  // row-major: values[r * cols + c]
  double at(std::size_t r, std::size_t c) const { return values[r * cols + c]; }
};

// "cols rows" header, then column-major values (any whitespace between them). kParseError naming
// path (and line) for a short, long, non-numeric or non-finite file, or a 0 x 0 header (libigl's
// binary DMAT, not supported).
Result<DenseMatrix> readDmat(const std::filesystem::path& path);
// readDmat on text already in memory; `source` stands for the path in the messages.
Result<DenseMatrix> parseDmat(const std::string& text, const std::string& source);

// A .dmat of V x B weights as sparse influences (zero weights dropped). kInvalidArgument naming
// the path if the size is not V x B, a weight is negative or non-finite, or a row does not sum to 1
// within 1e-6 (rows are not silently renormalised).
Result<Influences> readWeightsDmat(const std::filesystem::path& path, std::size_t vertex_count, std::size_t bone_count);

// 4B lines of 3 numbers: the columns of R_b then t_b (absolute, bind -> pose). Rotations are
// re-orthonormalised (the files carry ~6 digits): the nearest rotation (SVD polar factor) is kept.
// kInvalidArgument naming path and line: a line count other than 4B, a block farther than 1e-4
// (max entry) from a rotation, or a reflection (det -1). kParseError for a line that is not 3 numbers.
Result<std::vector<RigidTransform>> readTmat(const std::filesystem::path& path, std::size_t bone_count);
// readTmat on text already in memory; `source` stands for the path in the messages.
Result<std::vector<RigidTransform>> parseTmat(const std::string& text, const std::string& source, std::size_t bone_count);

// "dQ-<b>": [x, y, z, w] relative rotations; a missing bone is the identity; other keys are ignored.
// Quaternions are normalised. kParseError naming the path (and line for bad JSON): not an object,
// a key dQ-<b> with b not a number or >= bone_count, two keys naming one bone ("dQ-1", "dQ-01"),
// not 4 finite numbers, or length off 1 by > 1e-4.
Result<std::vector<glm::dquat>> readPoseJson(const std::filesystem::path& path, std::size_t bone_count);
// readPoseJson on text already in memory; `source` stands for the path in the messages.
Result<std::vector<glm::dquat>> parsePoseJson(const std::string& text, const std::string& source, std::size_t bone_count);

// libigl forward_kinematics with zero extra translation: root R_b = q_b, t_b = c - R_b c;
// child R_b = R_p q_b, t_b = t_p + R_p c - R_b c (c = the bone's head). Parents may come in any order.
// `relative`: unit quaternions; bones past its end are not rotated. Returns skeleton.boneCount()
// transforms. A parent out of range is treated as no parent, and a cycle of parents (validateRig
// rejects both) is broken at one of its bones, which becomes a root: bad input never hangs.
std::vector<RigidTransform> forwardKinematics(const Skeleton& skeleton, const std::vector<glm::dquat>& relative);

// Example poses with a libigl rig: the rest mesh is the bind mesh X, `poses` are OBJ files of the
// same topology, the skeleton comes from `tgf`; `weights` (.dmat, optional: distance weights are
// computed later) and `transforms` (one .Tmat per pose, optional: Kabsch-fitted later) complete it.
Result<ExampleSet> readLibiglExamples(const std::filesystem::path& rest, std::span<const std::filesystem::path> poses,
                                      const std::filesystem::path& tgf, const std::filesystem::path* weights,
                                      std::span<const std::filesystem::path> transforms);

}  // namespace odeskin
