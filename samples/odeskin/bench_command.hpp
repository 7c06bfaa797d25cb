// SPDX-License-Identifier: MIT
// `odeskin bench [--quick] --json OUT.json [--csv OUT.csv] [--plot OUT.png]` (issue 6): the
// per-frame cost of odeskin deformation, plain LBS and DQS on a real mesh tiled to each vertex
// count, per backend and thread count, verified against the double reference before timing, plus
// the fitting pipeline's stage times; the device, machine and build go into the report.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "console.hpp"

namespace CLI {
class App;
}

namespace odeskin {

struct BenchCommandOptions {
  bool quick = false;                     // < 1 minute: 32,185 vertices, N = 9
  std::filesystem::path json;             // required
  std::filesystem::path csv;              // optional
  std::filesystem::path plot;             // optional PNG
  std::filesystem::path fit_plot;         // optional PNG: fitting stages against vertices
  std::filesystem::path data = "../shared/data";  // cat-poses, horse-gallop (absent here, or "none": procedural arm, no fit table)
  std::vector<std::size_t> sizes;         // empty: the default for quick or full
  std::vector<int> terms;                 // empty: the default for quick or full
  std::string backends = "auto";          // auto (vulkan when a device opens), or a list of cpu_ref,cpu_fast,vulkan
  unsigned threads = 0;                   // cpu_fast's "all threads": 0 = the hardware's
  double min_time = 0.0;                  // seconds of timed frames per case; 0: 0.1 quick, 0.3 full
  bool fit = true;                        // --no-fit skips the stage table
  bool validation = false;                // Khronos validation layer on the Vulkan cases
};

// Exit status as console.hpp: 2 for bad options, 1 when a backend fails verification, the device
// asked for does not open, or an output cannot be written. Each output is written whole or not at
// all (temporary file + rename).
// Registers the verb on `app`, writing into `options`.
CLI::App* addBenchCommand(CLI::App& app, BenchCommandOptions& options);

int runBenchCommand(const BenchCommandOptions& options, Console& console, const std::string& device = "auto");

}  // namespace odeskin
