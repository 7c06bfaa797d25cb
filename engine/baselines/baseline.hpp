// SPDX-License-Identifier: MIT
// The common shape of every in-between method compared in the evaluation (issue 5): a deformer is
// built once from the key poses and the fitted asset, then evaluated frame by frame. A frame is a
// segment s (key s -> key s+1) and local time tau in [0, 1] (global time t = s + tau, key k at t = k),
// plus the skeleton at that frame when the caller has one.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "../core/status.hpp"
#include "../core/types.hpp"

namespace odeskin {

// Method names as the evaluation reports them (issue 5's JSON layout).
enum class BaselineMethod : std::uint32_t {
  kLinear = 0,        // linear vertex interpolation between the key poses
  kLbs,               // linear blend skinning of the bind mesh
  kDqs,               // dual-quaternion skinning of the bind mesh (Kavan et al. 2008)
  kPsdLbs,            // pose-space deformation (Lewis et al. 2000) on top of LBS
  kPsdDqs,            // pose-space deformation on top of DQS
  kFdCurve,           // finite differences along each iso-curve and in time (thesis 5.5)
  kOdeskinStatic,     // the analytic deformer with rho = eta = 0 (gamma_n = tau)
  kOdeskinDynamic,    // the analytic deformer with a skin material
};
inline constexpr std::uint32_t kBaselineMethodCount = 8;

// "linear", "lbs", "dqs", "psd_lbs", "psd_dqs", "fd_curve", "odeskin_static", "odeskin_dynamic".
std::string_view baselineMethodName(BaselineMethod method);
// The inverse of baselineMethodName; false for an unknown name.
bool parseBaselineMethod(std::string_view name, BaselineMethod* method);

struct BaselineFrameInput {
  std::uint32_t segment = 0;  // 0 .. K-2
  double tau = 0.0;           // [0, 1]; values outside are clamped
  // B bone transforms (bind space -> this frame), or empty. Given: the "truth" protocol (a skeleton
  // from the animation system, e.g. fitFrameBones on a ground-truth frame). Empty: the "keys"
  // protocol, the bones interpolated from the key poses (BaselineRig::keyBones, C1 across keys).
  // Methods without a skeleton (linear) ignore it.
  std::span<const BoneTransform> bones;
};

// Shared by the methods built from key poses: K >= 2 keys, all of `vertex_count` finite positions
// (vertex_count 0: the first key's size). `who` prefixes the messages.
Status checkKeyPoses(const std::vector<std::vector<Vec3>>& keys, std::size_t vertex_count, const char* who);

// Global time t (clamped to [0, K-1]) -> (segment, tau); t = K-1 is tau = 1 of the last segment.
std::pair<std::uint32_t, double> locateSegment(double t, std::uint32_t segment_count);

class Baseline {
 public:
  virtual ~Baseline() = default;

  virtual BaselineMethod method() const = 0;
  std::string_view name() const { return baselineMethodName(method()); }
  std::size_t vertexCount() const { return vertex_count_; }

  // Writes the V deformed positions of the frame into `out` (exactly V entries). Not thread-safe:
  // a deformer may keep per-frame scratch buffers. Errors: kInvalidArgument (out or bones of the
  // wrong size, a non-finite tau), kOutOfRange (segment >= K-1), and those of the skinning kernels.
  virtual Status evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) = 0;

 protected:
  explicit Baseline(std::size_t vertex_count) : vertex_count_(vertex_count) {}
  Baseline(const Baseline&) = default;
  Baseline(Baseline&&) = default;
  Baseline& operator=(const Baseline&) = default;
  Baseline& operator=(Baseline&&) = default;
  // The checks shared by every method; bone_count 0 skips the bone check.
  Status checkFrame(const BaselineFrameInput& frame, std::span<const Vec3> out, std::uint32_t segment_count,
                    std::size_t bone_count) const;

 private:
  std::size_t vertex_count_ = 0;
};

}  // namespace odeskin
