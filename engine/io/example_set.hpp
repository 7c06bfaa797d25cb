// SPDX-License-Identifier: MIT
// What the readers hand to the fitting pipeline: one mesh's topology, its bind (rest) positions,
// K >= 2 example poses of the same vertices, and whatever rig came with the files.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "../core/types.hpp"
#include "../rig/rig.hpp"

namespace odeskin {

struct ExampleSet {
  std::vector<Vec3> rest_positions;       // V topology vertices: the bind mesh X
  FaceList faces;                         // over topology vertices
  std::vector<std::vector<Vec3>> poses;   // K x V
  std::vector<std::string> pose_labels;   // K: file name, or "<file> animation A at t s", "<file> target k"
  std::optional<Rig> rig;                 // absent: derive one (--rig auto)
  RenderLayout render;                    // empty for OBJ input
  // What the reader accepted but a user should hear of, one line each, naming the file (a glTF
  // pose asked for outside its animation's keyframes, say). Callers print them as warnings.
  std::vector<std::string> warnings;
};

}  // namespace odeskin
