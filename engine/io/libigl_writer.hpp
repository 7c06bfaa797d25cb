// SPDX-License-Identifier: MIT
// Writers for the libigl text formats that libigl_io.hpp reads: a skeleton as .tgf and a dense
// matrix (skinning weights) as ASCII .dmat. Numbers are printed with 17 significant digits so a
// write and a read give back the same doubles; files are written through a temporary and renamed
// into place (writeFileAtomically), so a failure never leaves half a file.
#pragma once

#include <filesystem>
#include <span>

#include "../core/status.hpp"
#include "../rig/rig.hpp"

namespace odeskin {

// Joints: one per root head (root bones starting at the same point share it) and one per bone's
// tail; bone b is edge line b, from its head joint to its tail joint. A child bone starts at its
// parent's tail joint, so readTgf gives back the same bones, parents and joint positions.
// kInvalidArgument naming the bone: no bones, sizes differ, a non-finite joint, a parent out of
// range or on a cycle, or a child whose head is farther than 1e-9 of the skeleton's size from its
// parent's tail (a .tgf cannot hold that). kIoError naming the path when it cannot be written.
Status writeTgf(const std::filesystem::path& path, const Skeleton& skeleton);

// "cols rows" then the values column by column, one per line. `values` is row-major
// (rows x cols). kInvalidArgument when values.size() != rows x cols or a value is not finite.
Status writeDmat(const std::filesystem::path& path, std::size_t rows, std::size_t cols, std::span<const double> values);

// Influences as the dense V x B weights matrix readWeightsDmat reads (zeros where a bone has no
// weight). kInvalidArgument when the influences are invalid for `bone_count` bones.
Status writeWeightsDmat(const std::filesystem::path& path, const Influences& influences, std::size_t bone_count);

}  // namespace odeskin
