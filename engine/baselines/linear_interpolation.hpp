// SPDX-License-Identifier: MIT
// Linear vertex interpolation between example poses: in segment s (key s -> key s+1),
//   x_i(tau) = (1 - tau) P_{s,i} + tau P_{s+1,i},
// piecewise linear in the global time t = s + tau over the K keys. The baseline users get from a
// morph-target or vertex-cache blend: no skeleton, so turning limbs shrink toward their chords.
#pragma once

#include <vector>

#include "../core/result.hpp"
#include "baseline.hpp"

namespace odeskin {

class LinearInterpolation final : public Baseline {
 public:
  // `keys`: K >= 2 poses of V >= 1 vertices each. Errors: kInvalidArgument for fewer than 2 keys,
  // keys of different sizes, an empty mesh or a non-finite position (naming key and vertex).
  static Result<LinearInterpolation> create(std::vector<std::vector<Vec3>> keys);

  BaselineMethod method() const override { return BaselineMethod::kLinear; }
  // frame.bones is ignored.
  Status evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) override;

 private:
  explicit LinearInterpolation(std::vector<std::vector<Vec3>> keys);
  std::vector<std::vector<Vec3>> keys_;
};

}  // namespace odeskin
