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

// `odeskin bench --fit-plot OUT.png`: the fitting stages' milliseconds against vertex count, both on
// log scales, over the fits of the scaling series (the datasets named "... subdivided xL": one
// mesh refined), one line per stage and their sum without the rig, with a grey line of slope 1
// (time proportional to vertices) through the first sum and a cross at the thesis's total for its
// cat (3.66 ms at 7,207 vertices, Table 6.3). kInvalidArgument when the report has no
// such fits; kIoError naming the path.
Status writeFitPlot(const std::filesystem::path& path, const BenchReport& report);

}  // namespace odeskin::bench
