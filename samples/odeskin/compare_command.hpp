// SPDX-License-Identifier: MIT
// `odeskin compare MESH REFERENCE [--t T] [-o OUT.ply] [--heat-max E] [--json REPORT.json]`: the
// per-vertex error of a mesh against a reference with the same vertices (an in-between frame against
// ground truth, one method against another), as fractions of the reference's longest bounding-box
// side, the measure of `odeskin evaluate` and the thesis: the largest (MVE) with its vertex, the
// mean, the RMS and the 99th percentile. -o writes MESH as a PLY coloured by that error
// (engine/io/ply_writer.hpp) for MeshLab or Blender; --heat-max fixes the colour range so that
// several frames or methods share one scale.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "console.hpp"

namespace odeskin {

struct CompareOptions {
  std::filesystem::path mesh;       // .obj, .glb/.gltf or .odsk (render_inputs.hpp)
  std::filesystem::path reference;  // the same kinds, read at its default (an asset at t = 0)
  std::optional<double> t;          // MESH only: an asset's global time, a glTF's seconds
  std::filesystem::path ply;        // -o: MESH coloured by its error; empty: none
  std::optional<double> heat_max;   // top of the colour range, a fraction of the box; default: the MVE
  std::filesystem::path json;       // the report as JSON; empty: none
};

struct CompareReport {
  std::size_t vertices = 0;
  double box = 0.0;           // the reference's longest bounding-box side (absolute)
  double max_error = 0.0;     // fractions of the box
  std::size_t max_vertex = 0;
  double mean_error = 0.0;
  double rms_error = 0.0;
  double p99_error = 0.0;     // 99% of the vertices are within this
  double heat_max = 0.0;      // the PLY's colour range top (when written)
};

// Exit status as console.hpp: usage (2) for option errors (an output that is an input, a bad
// --heat-max or extension); failure (1) for unreadable inputs, different vertex counts (both named)
// and write errors.
int runCompareCommand(const CompareOptions& options, Console& console, CompareReport* report = nullptr);

}  // namespace odeskin
