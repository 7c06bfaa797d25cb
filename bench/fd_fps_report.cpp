// SPDX-License-Identifier: MIT
// Thesis Table 6.1 analogue (issue 5 point 3): frames per second of odeskin playback against the
// curve-based finite-difference method (thesis 5.5, engine/baselines/fd_curve_*) on the same fitted
// asset, same skin material, same machine, same run. Prints one Markdown table.
//
// What is timed, per frame of an animation through every key (frames spread uniformly in t):
// - odeskin reference: the closed-form time basis at tau (DeformPlayer::basisAt), the bones on their
//   key path (bonesAt) and the double-precision reference kernel (referenceJob) over every vertex.
// - odeskin fast: the same basis and bones, converted to float (toGpuBasis, toGpuBones), and
//   FourierDeformFastJob with 1 thread on the packed asset (the CPU twin of the GPU shader).
// - FD solve: the space-time finite-difference solve of every (segment, curve) (FdCurveSystem,
//   sparse LU, J = 32 points x T = 32 time levels per segment) divided by the time levels it
//   produces; a time step of the FD method is one frame, and it must be solved before it can be
//   shown. The factorisation (once per material) is reported apart.
// - FD playback: interpolating the solved levels at tau and the same reference kernel (the FD
//   method's output are curve coefficients, evaluated on the vertices like odeskin's).
// FD frames per second = 1 / (solve per level + playback per frame). Each figure is the fastest of
// `--repeats` passes (the machine is shared), after one warm-up pass.
//   odeskin_fd_fps_report [DATA_DIR] [--frames F] [--repeats R] [--quick]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine/baselines/fd_curve_deformer.hpp"
#include "engine/baselines/odeskin_baseline.hpp"
#include "engine/kernels/fourier_deform_fast_job.hpp"
#include "engine/kernels/lbs_job.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "bench/harness/numbered_paths.hpp"
#include "samples/decimal_integers.hpp"
#include "samples/main_guard.hpp"

namespace {

using namespace odeskin;
namespace fs = std::filesystem;
using odeskin::bench::numbered;
using Clock = std::chrono::steady_clock;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "odeskin_fd_fps_report: %s\n", what.c_str());
  std::fflush(nullptr);
  std::_Exit(1);  // not exit(), which is not thread-safe
}

template <typename T>
T orFail(Result<T> result, const std::string& what) {
  if (!result.ok()) fail(what + ": " + result.status().toString());
  return std::move(result).value();
}

void orFail(const Status& status, const std::string& what) {
  if (!status.ok()) fail(what + ": " + status.toString());
}

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Fastest of `repeats` passes after one warm-up, in seconds per call of `pass`.
double fastest(int repeats, const std::function<void()>& pass) {
  pass();
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const Clock::time_point start = Clock::now();
    pass();
    best = std::min(best, secondsSince(start));
  }
  return best;
}

struct Dataset {
  std::string name;
  std::vector<fs::path> keys;
};

struct Row {
  std::string name;
  std::size_t vertices = 0, curves = 0, segments = 0, levels = 0;
  double reference_ms = 0.0, fast_ms = 0.0, lbs_ms = 0.0;
  double fd_factor_ms = 0.0, fd_solve_ms = 0.0, fd_playback_ms = 0.0;
};

Row measure(const Dataset& set, int frames, int repeats) {
  const ExampleSet examples = orFail(readObjSequence(set.keys), set.name);
  PipelineOptions options;
  options.material = skinMaterial();
  const PipelineResult fit = orFail(runFitPipeline(examples, options), set.name + ": fit");
  // Every curve gets the skin material and its chained rates, for odeskin and FD alike.
  OdeskinBaseline odeskin =
      orFail(OdeskinBaseline::create(fit.asset, skinMaterial(), BaselineMethod::kOdeskinDynamic), "odeskin");
  const DeformAsset& asset = odeskin.asset();
  const DeformPlayer player = orFail(DeformPlayer::create(asset), "player");
  const PackedDeformData packed = orFail(packDeformAsset(asset), "pack");
  FdCurveOptions fd_options;
  fd_options.material = skinMaterial();

  Row row;
  row.name = set.name;
  row.vertices = asset.vertexCount();
  row.curves = asset.curveCount();
  row.segments = asset.segments.size();
  // Frame f at global time t = f (K - 1) / (F - 1): the whole animation, keys included.
  std::vector<std::pair<std::uint32_t, double>> at;
  at.reserve(static_cast<std::size_t>(frames));
  for (int f = 0; f < frames; ++f) {
    at.push_back(player.locate(static_cast<double>(f) * static_cast<double>(row.segments) / (frames - 1)));
  }
  std::vector<ModeBasisValue> basis(player.basisSize());
  std::vector<BoneTransform> bones(asset.bone_count);
  std::vector<gpu::ModeBasis> gpu_basis(basis.size());
  std::vector<gpu::BoneMatrix> gpu_bones(bones.size());
  std::vector<Vec3> out(row.vertices);
  std::vector<gpu::Float4> fast_out(row.vertices);
  const double per_pass = 1e3 / frames;  // seconds per pass -> ms per frame

  row.reference_ms = per_pass * fastest(repeats, [&] {
    for (const auto& [segment, tau] : at) {
      player.basisAt(tau, basis);
      player.bonesAt(asset, segment, tau, bones);
      orFail(referenceJob(asset, segment, basis, bones, out).run(), "reference job");
    }
  });
  row.fast_ms = per_pass * fastest(repeats, [&] {
    for (const auto& [segment, tau] : at) {
      player.basisAt(tau, basis);
      player.bonesAt(asset, segment, tau, bones);
      toGpuBasis(basis, gpu_basis);
      toGpuBones(bones, gpu_bones);
      orFail(FourierDeformFastJob{&packed, segment, gpu_bones, gpu_basis, fast_out, 1}.run(), "fast job");
    }
  });
  row.lbs_ms = per_pass * fastest(repeats, [&] {
    for (const auto& [segment, tau] : at) {
      player.bonesAt(asset, segment, tau, bones);
      orFail(LbsJob{asset.rest_positions, asset.influences, bones, out}.run(), "LBS job");
    }
  });

  // FD: set-up (factorisation, then every space-time solve) as often as the other passes.
  double factor = 1e300, solve = 1e300;
  std::optional<FdCurveDeformer> fd;
  for (int r = 0; r <= repeats; ++r) {
    fd.emplace(orFail(FdCurveDeformer::create(asset, fd_options), "fd curve"));
    if (r == 0) continue;  // warm-up
    factor = std::min(factor, fd->stats().seconds_factor);
    solve = std::min(solve, fd->stats().seconds_solve);
  }
  row.levels = row.segments * fd->steps();
  row.fd_factor_ms = 1e3 * factor;
  row.fd_solve_ms = 1e3 * solve / static_cast<double>(row.levels);
  row.fd_playback_ms = per_pass * fastest(repeats, [&] {
    for (const auto& [segment, tau] : at) {
      player.bonesAt(asset, segment, tau, bones);
      orFail(fd->evaluate({segment, tau, bones}, out), "fd evaluate");
    }
  });
  return row;
}

}  // namespace

static int run(int argc, char** argv) {
  std::string data_text = ODESKIN_DATA_DIR;
  int frames = 120;
  int repeats = 3;
  bool quick = false;
  CLI::App app("odeskin_fd_fps_report: odeskin against the finite-difference solver, frames per second "
               "(thesis Table 6.1)");
  app.add_option("data", data_text, "The shared data folder (default " ODESKIN_DATA_DIR ")");
  app.add_option("--frames", frames, "Frames per pass over the animation (default 120)")->check(CLI::Range(2, 1000000));
  app.add_option("--repeats", repeats, "Passes; the fastest is printed (default 3)")->check(CLI::Range(1, 1000));
  app.add_flag("--quick", quick, "The horse only");
  odeskin::requireDecimalIntegers(app);
  CLI11_PARSE(app, argc, argv);
  const fs::path data = data_text;
  std::vector<Dataset> sets;
  sets.push_back({"horse-gallop frames 1-25, keys every 4",
                  numbered(data / "horse-gallop", "horse-%02d.obj", {1, 5, 9, 13, 17, 21, 25})});
  if (!quick) sets.push_back({"cat-poses 00-09", numbered(data / "cat-poses", "cat-%02d.obj", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9})});

  std::printf("Per frame, fastest of %d passes of %d frames over the whole animation (ms; fps in brackets).\n\n",
              repeats, frames);
  std::printf("| dataset | vertices | curves | segments | odeskin reference (double) | odeskin fast (float, 1 thread) "
              "| FD solve per time level | FD playback | FD total | FD factorisation (once) | LBS alone (double) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Dataset& set : sets) {
    const Row r = measure(set, frames, repeats);
    const double fd_total = r.fd_solve_ms + r.fd_playback_ms;
    std::printf("| %s | %zu | %zu | %zu | %.3f (%.0f) | %.3f (%.0f) | %.3f | %.3f | %.3f (%.0f) | %.1f | %.3f (%.0f) |\n",
                r.name.c_str(), r.vertices, r.curves, r.segments, r.reference_ms, 1e3 / r.reference_ms, r.fast_ms,
                1e3 / r.fast_ms, r.fd_solve_ms, r.fd_playback_ms, fd_total, 1e3 / fd_total, r.fd_factor_ms, r.lbs_ms,
                1e3 / r.lbs_ms);
    std::fflush(stdout);
  }
  return 0;
}

int main(int argc, char** argv) { return odeskin::runGuarded("odeskin_fd_fps_report", run, argc, argv); }
