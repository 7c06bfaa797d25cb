// SPDX-License-Identifier: MIT
#include "deform_cases.hpp"

#include <chrono>
#include <cmath>
#include <optional>
#include <span>

#include <glm/geometric.hpp>

#include "bench_subject.hpp"
#include "engine/core/number_text.hpp"
#include "engine/kernels/cpu_deform_kernel.hpp"
#include "engine/kernels/lbs_job.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/offline/residual_fit.hpp"
#include "frame_timer.hpp"
#include "frame_traffic.hpp"
#include "host/gpu_deformer.hpp"
#include "host/gpu_lbs.hpp"

namespace odeskin::bench {
namespace {

using Clock = std::chrono::steady_clock;

// Untimed frames before a Vulkan case is timed: a GPU idles at a low clock (an H200 at 345 MHz,
// against 1,980 busy). In the one mixed CPU and Vulkan run on an H200 some Vulkan cases took up to
// 4.7x their Vulkan-only GPU time, for a reason not established (docs/performance.md, "On a GPU");
// a warm GPU at least rules the clock out. CPUs reach their clock within one warm-up frame.
constexpr double kGpuWarmupSeconds = 0.25;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Worst |actual - expected| / box; NaN counts as infinitely wrong.
double worstError(std::span<const Vec3> expected, std::span<const gpu::Float4> actual, double box) {
  double worst = 0.0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const double e = glm::length(Vec3(actual[i].x, actual[i].y, actual[i].z) - expected[i]);
    worst = std::isnan(e) ? INFINITY : std::max(worst, e);
  }
  return worst / box;
}

// One kernel on one subject: the reference output and a place to put records.
class CaseRunner {
 public:
  CaseRunner(const BenchSubject& subject, const std::string& kernel, int terms, const DeformCaseOptions& options,
             std::vector<BenchRecord>& out)
      : s_(subject), kernel_(kernel), terms_(terms), options_(options), out_(out) {}

  bool deforms() const { return kernel_ == "odeskin"; }

  Status run() {
    ODESKIN_TRY(computeExpected());
    if (options_.cpu_ref) ODESKIN_TRY(runCpuRef());
    if (options_.cpu_fast) {
      ODESKIN_TRY(runCpuFast(1));
      if (options_.all_threads > 1) ODESKIN_TRY(runCpuFast(options_.all_threads));
    }
    if (options_.vulkan) ODESKIN_TRY(runVulkan());
    return okStatus();
  }

 private:
  Status computeExpected() {
    expected_.resize(s_.vertexCount());
    ODESKIN_TRY(reference(expected_));
    box_ = longestBoxSide(expected_);
    // One vertex has no box (--sizes 1 read "differs by inf"): its distance from the origin is the scale.
    if (!(box_ > 0.0) && !expected_.empty()) box_ = glm::length(expected_.front());
    if (!(box_ > 0.0)) box_ = 1.0;
    bytes_per_frame_ = static_cast<double>(frameBytes(s_.packed, s_.frame.segment, deforms()));
    return okStatus();
  }

  Status reference(std::span<Vec3> out) const {
    if (deforms()) return referenceJob(s_.asset, s_.frame.segment, s_.frame.basis, s_.frame.bones, out).run();
    return skinningReference(out);
  }

  Status skinningReference(std::span<Vec3> out) const {
    return LbsJob{s_.asset.rest_positions, s_.asset.influences, s_.frame.bones, out, s_.asset.skinning}.run();
  }

  BenchRecord record(const char* backend, unsigned threads) const {
    BenchRecord r;
    r.kernel = kernel_;
    r.backend = backend;
    r.threads = threads;
    r.vertices = s_.vertexCount();
    r.terms = deforms() ? terms_ : 0;
    r.bytes_per_frame = bytes_per_frame_;
    return r;
  }

  Status finish(BenchRecord r, const FrameTiming& timing) {
    r.seconds_per_frame = timing.seconds;
    r.gpu_seconds_per_frame = timing.gpu_seconds;
    r.frames = timing.frames;
    if (options_.progress) {
      char line[256];
      std::snprintf(line, sizeof line, "%-7s %-8s %2u thr V=%-8zu N=%-2d %12.1f us/frame %9.2f Mvert/s  err %.1e",
                    r.kernel.c_str(), r.backend.c_str(), r.threads, r.vertices, r.terms, r.seconds_per_frame * 1e6,
                    r.verticesPerSecond() * 1e-6, r.max_error);
      options_.progress(line);
    }
    out_.push_back(std::move(r));
    return okStatus();
  }

  Status check(BenchRecord& r, std::span<const gpu::Float4> actual) const {
    r.max_error = worstError(expected_, actual, box_);
    return checkError(r.kernel, r, r.max_error);
  }

  Status checkError(const std::string& kernel, const BenchRecord& r, double error) const {
    if (!(error <= kVerifyTolerance)) {
      return internalError("bench: " + kernel + " on " + r.backend + " (" + std::to_string(r.threads) +
                           " threads, " + std::to_string(r.vertices) + " vertices) differs from cpu_ref by " +
                           messageNumber(error) + " of the box (limit 1e-4)");
    }
    return okStatus();
  }

  // odeskin only: its frames against LBS frames of the same subject on the same backend, alternated
  // (timePairedFrames), into r's paired ratios. `skin` has run once into `skinned`, which is checked
  // against the LBS reference first, so the pairing never times a wrong kernel.
  Status pairWithLbs(BenchRecord& r, const FrameBody& deform, const FrameBody& skin,
                     std::span<const gpu::Float4> skinned, double warmup_seconds) {
    // Computed once for the backends that pair (cpu_fast on 1 and all threads, vulkan).
    if (skinned_expected_.empty()) {
      skinned_expected_.resize(s_.vertexCount());
      ODESKIN_TRY(skinningReference(skinned_expected_));
    }
    ODESKIN_TRY(checkError("lbs (paired with odeskin)", r, worstError(skinned_expected_, skinned, box_)));
    ODESKIN_ASSIGN_OR_RETURN(const PairedTiming paired,
                             timePairedFrames(deform, skin, options_.min_seconds, 3, 100000, warmup_seconds));
    r.paired_over_lbs = paired.ratio;
    r.paired_gpu_over_lbs = paired.gpu_ratio;
    return okStatus();
  }

  Status runCpuRef() {
    std::vector<Vec3> out(s_.vertexCount());
    ODESKIN_ASSIGN_OR_RETURN(const FrameTiming t, timeFrames([&](double&) { return reference(out); },
                                                             options_.min_seconds));
    return finish(record("cpu_ref", 1), t);
  }

  Status runCpuFast(unsigned threads) {
    BenchRecord r = record("cpu_fast", threads);
    std::vector<gpu::Float4> out(s_.vertexCount());
    const Clock::time_point prepare = Clock::now();
    ODESKIN_ASSIGN_OR_RETURN(const CpuDeformKernel kernel, CpuDeformKernel::create(s_.packed));
    r.upload_seconds = secondsSince(prepare);
    const BenchFrame& f = s_.frame;
    auto frame = [&](double&) {
      return deforms() ? kernel.deform(f.segment, f.gpu_bones, f.gpu_basis, out, threads)
                       : kernel.skin(f.gpu_bones, out, threads);
    };
    double unused = 0.0;
    ODESKIN_TRY(frame(unused));
    ODESKIN_TRY(check(r, out));
    ODESKIN_ASSIGN_OR_RETURN(const FrameTiming t, timeFrames(frame, options_.min_seconds));
    if (deforms()) {
      std::vector<gpu::Float4> skinned(s_.vertexCount());
      const FrameBody skin = [&](double&) { return kernel.skin(f.gpu_bones, skinned, threads); };
      ODESKIN_TRY(skin(unused));
      ODESKIN_TRY(pairWithLbs(r, frame, skin, skinned, 0.0));
    }
    return finish(std::move(r), t);
  }

  Status runVulkan() {
    if (options_.device == nullptr) return invalidArgument("bench: vulkan cases need a Vulkan device");
    BenchRecord r = record("vulkan", 1);
    std::vector<gpu::Float4> out(s_.vertexCount());
    std::optional<GpuDeformer> deformer;
    std::optional<GpuLbs> lbs;
    const Clock::time_point upload = Clock::now();
    if (deforms()) {
      ODESKIN_ASSIGN_OR_RETURN(deformer, GpuDeformer::create(*options_.device, s_.packed));
    } else {
      ODESKIN_ASSIGN_OR_RETURN(lbs, GpuLbs::create(*options_.device, s_.packed));
    }
    r.upload_seconds = secondsSince(upload);
    // odeskin's frames are also paired with LBS frames on the same device (pairWithLbs).
    if (deforms()) {
      ODESKIN_ASSIGN_OR_RETURN(lbs, GpuLbs::create(*options_.device, s_.packed));
    }
    const GpuDeformFrame deform_frame{s_.frame.segment, s_.frame.gpu_bones, s_.frame.gpu_basis};
    const GpuLbsFrame lbs_frame{s_.frame.gpu_bones};
    auto frame = [&](double& gpu_seconds) {
      Status status = deformer ? deformer->run(deform_frame) : lbs->run(lbs_frame);
      gpu_seconds = deformer ? deformer->lastGpuSeconds() : lbs->lastGpuSeconds();
      return status;
    };
    double unused = 0.0;
    ODESKIN_TRY(frame(unused));
    ODESKIN_TRY(deformer ? deformer->readPositions(out) : lbs->readPositions(out));
    ODESKIN_TRY(check(r, out));
    ODESKIN_ASSIGN_OR_RETURN(const FrameTiming t,
                             timeFrames(frame, options_.min_seconds, 3, 100000, kGpuWarmupSeconds));
    if (deforms()) {
      const FrameBody skin = [&](double& gpu_seconds) {
        Status status = lbs->run(lbs_frame);
        gpu_seconds = lbs->lastGpuSeconds();
        return status;
      };
      ODESKIN_TRY(skin(unused));
      ODESKIN_TRY(lbs->readPositions(out));
      ODESKIN_TRY(pairWithLbs(r, frame, skin, out, kGpuWarmupSeconds));
    }
    return finish(std::move(r), t);
  }

  const BenchSubject& s_;
  std::string kernel_;
  int terms_ = 0;
  const DeformCaseOptions& options_;
  std::vector<BenchRecord>& out_;
  std::vector<Vec3> expected_;
  std::vector<Vec3> skinned_expected_;  // odeskin: the LBS reference its pairing checks against
  double box_ = 1.0;
  double bytes_per_frame_ = 0.0;  // the same for every backend
};

}  // namespace

Status runDeformCases(const std::map<int, DeformAsset>& sources, const DeformCaseOptions& options,
                      std::vector<BenchRecord>& out) {
  if (options.vulkan && options.device == nullptr) return invalidArgument("bench: vulkan cases need a Vulkan device");
  for (int n : options.terms) {
    if (!sources.count(n)) return invalidArgument("bench: no fitted asset with N = " + std::to_string(n));
  }
  for (std::size_t size : options.sizes) {
    for (int n : options.terms) {
      ODESKIN_ASSIGN_OR_RETURN(const BenchSubject subject,
                               makeSubject(sources.at(n), size, SkinningMode::kLinear, options.time));
      ODESKIN_TRY(CaseRunner(subject, "odeskin", n, options, out).run());
      if (n == options.terms.back()) ODESKIN_TRY(CaseRunner(subject, "lbs", 0, options, out).run());
    }
    // Skinning does not depend on N: DQS runs once per size, on the last N's asset.
    ODESKIN_ASSIGN_OR_RETURN(const BenchSubject dqs,
                             makeSubject(sources.at(options.terms.back()), size, SkinningMode::kDualQuaternion,
                                         options.time));
    ODESKIN_TRY(CaseRunner(dqs, "dqs", 0, options, out).run());
  }
  return okStatus();
}

}  // namespace odeskin::bench
