// SPDX-License-Identifier: MIT
// One parameter v for neighbouring curves (thesis 6.3.1, MATH.md 4.1): a vertex between curves a
// and b evaluates both series at the same v, so their points must correspond. Every curve of a
// part runs counter-clockwise about the part's flow times one sign per part, and starts at the
// point seen from its centroid closest to a reference direction carried from plane to plane
// (projected onto each one, parallel transport in the small). Sign and first reference come
// from a neighbour part done before whose nearest curve is parallel (so junction blends match),
// else from the parent part. v is the normalised arc length on the bind mesh.
#pragma once

#include <span>

#include "../core/types.hpp"
#include "part_curves.hpp"
#include "part_segmentation.hpp"

namespace odeskin {

// Orients, rotates and parametrises every curve in the sequences, parts in seg.order. A curve
// whose arc length is zero is marked dropped.
void orientCurves(std::span<const Vec3> rest, const Segmentation& seg, CurveLayout& layout);

}  // namespace odeskin
