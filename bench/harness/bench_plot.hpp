// SPDX-License-Identifier: MIT
// `odeskin bench --plot OUT.png`: throughput (vertices per second) against vertex count, both on
// log scales, one line per (case, backend, threads) at one N, so the knee where a backend stops
// scaling and the gap between odeskin and plain skinning read off one picture.
#pragma once

#include <filesystem>

#include "bench_report.hpp"
#include "engine/core/status.hpp"

namespace odeskin::bench {

// Plots the odeskin records at N = `terms` (or the largest N below it present) with the lbs and dqs
// records. kInvalidArgument when there is nothing to plot; kIoError naming the path.
Status writePlot(const std::filesystem::path& path, const BenchReport& report, int terms = 9);

}  // namespace odeskin::bench
