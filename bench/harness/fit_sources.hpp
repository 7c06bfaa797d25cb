// SPDX-License-Identifier: MIT
// The fits the harness needs: the mesh every per-frame case tiles (cat-poses 00-02, fitted once per
// N; the procedural arm when the data folder is absent), and the fitting pipeline's stage times
// (the thesis's Table 6.3 columns) per dataset and on ever larger subdivisions of the cat.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "bench_report.hpp"
#include "engine/core/result.hpp"
#include "engine/offline/deform_asset.hpp"

namespace odeskin::bench {

struct FitSources {
  std::string mesh;                   // what was fitted, for the report
  std::map<int, DeformAsset> assets;  // by N
  std::vector<FitStageRecord> fits;   // the fits that made them
};

// kIoError/kInvalidArgument from the readers, naming the file, when data_dir exists but is broken.
Result<FitSources> fitSources(const std::filesystem::path& data_dir, std::span<const int> terms);

struct FitStageOptions {
  bool quick = false;       // quick: the cat with 2 poses, and one subdivision level
  int max_subdivisions = 4;  // the cat's 7,207 vertices x ~4 per level: 4 levels reach 1.8 million
  // Fits of meshes below `repeat_below_vertices` run `repeats` times and keep each stage's fastest
  // time (and the fastest total): milliseconds on a shared machine swing with its other load.
  // Not in a quick run.
  int repeats = 3;
  std::size_t repeat_below_vertices = 200000;
  std::function<void(const std::string&)> progress;
};

// Every fit of the stage table, N = 9, skin material. kIoError when data_dir lacks the data.
Result<std::vector<FitStageRecord>> timeFitStages(const std::filesystem::path& data_dir, const FitStageOptions& options);

}  // namespace odeskin::bench
