// SPDX-License-Identifier: MIT
#include "linear_interpolation.hpp"

#include <algorithm>
#include <string>

namespace odeskin {

LinearInterpolation::LinearInterpolation(std::vector<std::vector<Vec3>> keys)
    : Baseline(keys.front().size()), keys_(std::move(keys)) {}

Result<LinearInterpolation> LinearInterpolation::create(std::vector<std::vector<Vec3>> keys) {
  ODESKIN_TRY(checkKeyPoses(keys, 0, "linear"));
  return LinearInterpolation(std::move(keys));
}

Status LinearInterpolation::evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) {
  ODESKIN_TRY(checkFrame(frame, out, static_cast<std::uint32_t>(keys_.size() - 1), 0));
  const double tau = std::clamp(frame.tau, 0.0, 1.0);
  const std::vector<Vec3>& a = keys_[frame.segment];
  const std::vector<Vec3>& b = keys_[frame.segment + 1];
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = (1.0 - tau) * a[i] + tau * b[i];
  return okStatus();
}

}  // namespace odeskin
