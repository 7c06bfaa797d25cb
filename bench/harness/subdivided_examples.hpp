// SPDX-License-Identifier: MIT
// Larger versions of a real example set for the fitting-time scaling curve: midpoint subdivision
// (every triangle into four, a new vertex at each edge's midpoint) applied to the rest mesh and
// every pose alike, so the poses stay one mesh. A rig, when given, is carried over: a midpoint
// vertex takes half of each end's weights, and the bones and key transforms are unchanged.
#pragma once

#include "engine/core/result.hpp"
#include "engine/io/example_set.hpp"

namespace odeskin::bench {

// kInvalidArgument when a face is not a triangle or an index is out of range.
Result<ExampleSet> subdivideMidpoint(const ExampleSet& examples);

}  // namespace odeskin::bench
