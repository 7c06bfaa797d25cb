// SPDX-License-Identifier: MIT
// Example sets built from ../shared/data for the pipeline's acceptance tests (issue 3, point 7).
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/io/libigl_io.hpp"
#include "engine/io/obj_reader.hpp"

namespace odeskin::testing {

inline std::filesystem::path dataDir() { return std::filesystem::path(ODESKIN_DATA_DIR); }

inline std::vector<std::filesystem::path> horseFrames(std::initializer_list<int> frames) {
  std::vector<std::filesystem::path> paths;
  char name[32];
  for (int f : frames) {
    std::snprintf(name, sizeof(name), "horse-%02d.obj", f);
    paths.push_back(dataDir() / "horse-gallop" / name);
  }
  return paths;
}

inline std::vector<std::filesystem::path> catPoses(int count) {
  std::vector<std::filesystem::path> paths;
  char name[32];
  for (int k = 0; k < count; ++k) {
    std::snprintf(name, sizeof(name), "cat-%02d.obj", k);
    paths.push_back(dataDir() / "cat-poses" / name);
  }
  return paths;
}

// The cylinder with its ground-truth rig: rest mesh, poses-1 meshes, skeleton, weights, transforms.
inline Result<ExampleSet> cylinderWithRig(bool with_weights, bool with_transforms) {
  const std::filesystem::path dir = dataDir() / "cylinder";
  std::vector<std::filesystem::path> poses, tmats;
  for (int k = 1; k <= 4; ++k) {
    poses.push_back(dir / "poses-1" / ("cylinder-" + std::to_string(k) + ".obj"));
    tmats.push_back(dir / "poses-1" / ("cylinder-" + std::to_string(k) + ".Tmat"));
  }
  const std::filesystem::path weights = dir / "cylinder.DMAT";
  return readLibiglExamples(dir / "cylinder.obj", poses, dir / "cylinder.tgf", with_weights ? &weights : nullptr,
                            with_transforms ? std::span<const std::filesystem::path>(tmats)
                                            : std::span<const std::filesystem::path>());
}

}  // namespace odeskin::testing
