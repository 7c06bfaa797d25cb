// SPDX-License-Identifier: MIT
#include "fd_curve_deformer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include "../kernels/fourier_deform_job.hpp"
#include "../offline/deform_player.hpp"
#include "fd_curve_system.hpp"

namespace odeskin {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// cos and sin of 2 pi n j / J for n = 1..N, j = 0..J-1 (row j, column n - 1).
struct DftTable {
  std::size_t points = 0;
  int modes = 0;
  std::vector<double> cosines, sines;

  DftTable(std::size_t j_count, int n_modes) : points(j_count), modes(n_modes) {
    cosines.resize(j_count * static_cast<std::size_t>(n_modes));
    sines.resize(cosines.size());
    for (std::size_t j = 0; j < j_count; ++j) {
      for (int n = 1; n <= n_modes; ++n) {
        const double angle = 2.0 * std::numbers::pi * n * static_cast<double>(j) / static_cast<double>(j_count);
        cosines[j * static_cast<std::size_t>(n_modes) + static_cast<std::size_t>(n - 1)] = std::cos(angle);
        sines[j * static_cast<std::size_t>(n_modes) + static_cast<std::size_t>(n - 1)] = std::sin(angle);
      }
    }
  }
  double c(std::size_t j, int n) const { return cosines[j * static_cast<std::size_t>(modes) + static_cast<std::size_t>(n - 1)]; }
  double s(std::size_t j, int n) const { return sines[j * static_cast<std::size_t>(modes) + static_cast<std::size_t>(n - 1)]; }

  // The periodic part of a curve's series (coefficients 0..2N of the layout) at v_j = j / J.
  void sample(const Vec3* d, std::span<Vec3> out) const {
    for (std::size_t j = 0; j < points; ++j) {
      Vec3 sum = d[0];
      for (int n = 1; n <= modes; ++n) sum += c(j, n) * d[2 * n - 1] + s(j, n) * d[2 * static_cast<std::size_t>(n)];
      out[j] = sum;
    }
  }
  // Its inverse for J > 2N: the mean and (2 / J) sum u_j cos / sin (MATH.md 4.2's uniform shortcut).
  void analyse(const Vec3* u, Vec3* d) const {
    const double inv = 1.0 / static_cast<double>(points);
    d[0] = Vec3(0.0);
    for (std::size_t j = 0; j < points; ++j) d[0] += inv * u[j];
    for (int n = 1; n <= modes; ++n) {
      Vec3 a(0.0), b(0.0);
      for (std::size_t j = 0; j < points; ++j) {
        a += c(j, n) * u[j];
        b += s(j, n) * u[j];
      }
      d[2 * n - 1] = 2.0 * inv * a;
      d[2 * static_cast<std::size_t>(n)] = 2.0 * inv * b;
    }
  }
};

}  // namespace

FdCurveDeformer::FdCurveDeformer(DeformAsset asset, BaselineRig rig)
    : Baseline(asset.vertexCount()), asset_(std::move(asset)), rig_(std::move(rig)) {}

Result<FdCurveDeformer> FdCurveDeformer::create(const DeformAsset& asset, const FdCurveOptions& options) {
  ODESKIN_TRY(validateDeformAsset(asset));
  const int modes = asset.modes;
  if (options.points <= 2u * static_cast<std::uint32_t>(modes)) {
    return invalidArgument("fd curve: " + std::to_string(options.points) + " grid points cannot carry N = " +
                           std::to_string(modes) + " modes (needs J > 2N)");
  }
  if (options.steps < 2) return invalidArgument("fd curve: needs at least 2 time steps, got " + std::to_string(options.steps));
  DeformAsset copy = asset;
  if (options.material) {
    copy.materials = {*options.material};
    copy.curve_materials.assign(copy.curveCount(), 0u);
  }
  ODESKIN_ASSIGN_OR_RETURN(BaselineRig rig, BaselineRig::fromAsset(copy));
  FdCurveDeformer fd(std::move(copy), std::move(rig));
  const DeformAsset& a = fd.asset_;
  const std::size_t j_count = options.points;
  const std::size_t t_count = options.steps;
  const std::size_t c_count = a.curveCount();
  const std::size_t m_count = coefficientsPerCurve(modes);
  fd.steps_ = options.steps;

  Clock::time_point start = Clock::now();
  std::vector<FdCurveSystem> periodic, trend;
  for (std::size_t m = 0; m < a.materials.size(); ++m) {
    for (const std::uint32_t points : {options.points, 1u}) {
      Result<FdCurveSystem> system = FdCurveSystem::create(a.materials[m], points, options.steps);
      if (!system.ok()) return Status(system.status().code(), "material " + std::to_string(m) + ": " + system.status().message());
      (points == 1u ? trend : periodic).push_back(std::move(*system));
    }
  }
  fd.stats_.factorizations = 2 * a.materials.size();
  fd.stats_.unknowns_per_system = j_count * t_count;
  fd.stats_.seconds_factor = secondsSince(start);

  start = Clock::now();
  const DftTable dft(j_count, modes);
  fd.levels_.assign(a.segments.size(), std::vector<Vec3>((t_count + 1) * c_count * m_count));
  std::vector<Vec3> target(j_count), rate(j_count), grid((t_count + 1) * j_count);
  std::vector<Vec3> trend_target(1), trend_rate(1), trend_grid(t_count + 1);
  for (std::size_t c = 0; c < c_count; ++c) {
    const FdCurveSystem& sys = periodic[a.curve_materials[c]];
    const FdCurveSystem& line = trend[a.curve_materials[c]];
    for (std::size_t s = 0; s < a.segments.size(); ++s) {
      const Vec3* d = a.segments[s].coefficients.data() + c * m_count;
      dft.sample(d, target);
      trend_target[0] = d[m_count - 1];
      const bool at_rest = s == 0;
      Status solved = sys.solve(target, at_rest ? std::span<const Vec3>() : rate, grid);
      if (solved.ok()) solved = line.solve(trend_target, at_rest ? std::span<const Vec3>() : trend_rate, trend_grid);
      if (!solved.ok()) {
        return Status(solved.code(), "segment " + std::to_string(s) + " curve " + std::to_string(c) + ": " + solved.message());
      }
      for (std::size_t n = 0; n <= t_count; ++n) {
        Vec3* level = fd.levels_[s].data() + (n * c_count + c) * m_count;
        dft.analyse(grid.data() + n * j_count, level);
        level[m_count - 1] = trend_grid[n];
      }
      sys.endRates(grid, rate);
      line.endRates(trend_grid, trend_rate);
      ++fd.stats_.curve_solves;
    }
  }
  fd.stats_.seconds_solve = secondsSince(start);
  fd.coefficients_.resize(c_count * m_count);
  fd.basis_.assign(a.materials.size() * static_cast<std::size_t>(modes + 1) + 1, ModeBasisValue{1.0, 0.0});
  return fd;
}

std::span<const Vec3> FdCurveDeformer::levelCoefficients(std::uint32_t segment, std::uint32_t n) const {
  const std::size_t per_level = coefficients_.size();
  return std::span<const Vec3>(levels_[segment]).subspan(n * per_level, per_level);
}

Status FdCurveDeformer::evaluate(const BaselineFrameInput& frame, std::span<Vec3> out) {
  ODESKIN_TRY(checkFrame(frame, out, static_cast<std::uint32_t>(levels_.size()), asset_.bone_count));
  const double tau = std::clamp(frame.tau, 0.0, 1.0);
  const double x = tau * static_cast<double>(steps_);
  const std::uint32_t n = std::min(static_cast<std::uint32_t>(x), steps_ - 1);
  const double lambda = x - static_cast<double>(n);
  const std::span<const Vec3> lo = levelCoefficients(frame.segment, n);
  const std::span<const Vec3> hi = levelCoefficients(frame.segment, n + 1);
  for (std::size_t k = 0; k < coefficients_.size(); ++k) coefficients_[k] = (1.0 - lambda) * lo[k] + lambda * hi[k];
  basis_.back() = ModeBasisValue{remainderWeight(tau), 0.0};
  const std::span<const BoneTransform> bones = rig_.frameBones(frame.segment, tau, frame.bones, bones_);
  FourierDeformJob job = referenceJob(asset_, frame.segment, basis_, bones, out);
  job.coefficients = coefficients_;
  job.rates = {};
  return job.run();
}

}  // namespace odeskin
