// SPDX-License-Identifier: MIT
// The bytes one frame must move at least (issue 6: "report vertices/s and bytes/s against the
// device's memory bandwidth"): every array of PackedDeformData's float32 layout the frame's kernel
// reads, each counted once, and the positions it writes. Per vertex: the rest position, the
// influences and the output, and for odeskin the binding and the segment's corrective; per frame:
// the bones (and their dual quaternions), and for odeskin the segment's coefficients (and rates),
// the curves' materials, the time basis and the segment's remainders. A lower bound on memory
// traffic: cache misses, or a GPU pass's intermediate (the folded coefficients, C x (2N + 2) x 16
// bytes written and read again), add to it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/kernels/packed_deform.hpp"

namespace odeskin::bench {

// `deforms`: the odeskin frame of segment `segment` (< d.segment_count); false: skinning alone, with
// d.skinning's bones.
std::size_t frameBytes(const PackedDeformData& d, std::uint32_t segment, bool deforms);

}  // namespace odeskin::bench
