// SPDX-License-Identifier: MIT
// The harness's results and their file formats. The JSON layout is a contract (issue 6; scripts
// rely on it): {"device": ..., "records": [{"case", "backend", "threads", "vertices", "terms",
// "seconds_per_frame", "vertices_per_second", ...}]}, with more keys added beside those, never
// renamed.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/status.hpp"

namespace odeskin::bench {

struct BenchRecord {
  std::string kernel;        // JSON "case": lbs, dqs or odeskin
  std::string backend;       // cpu_ref, cpu_fast or vulkan
  unsigned threads = 1;      // CPU worker threads (1 for vulkan: the submitting thread)
  std::size_t vertices = 0;
  int terms = 0;             // N; 0 for lbs and dqs
  double seconds_per_frame = 0.0;   // median wall time, submit to results ready
  double gpu_seconds_per_frame = 0.0;  // vulkan: median timestamp-query time of the dispatch
  double upload_seconds = 0.0;      // one-off: GPU upload, or the CPU path's preparation
  int frames = 0;                   // frames timed
  double max_error = 0.0;           // worst |p - p_ref| / longest box side against cpu_ref
  double bytes_per_frame = 0.0;     // the least a frame moves (frame_traffic.hpp)
  // odeskin on cpu_fast and vulkan: odeskin / LBS on the same subject, backend and threads, frame
  // against frame (timePairedFrames), wall and GPU time; 0 where not measured.
  double paired_over_lbs = 0.0;
  double paired_gpu_over_lbs = 0.0;

  double verticesPerSecond() const { return seconds_per_frame > 0.0 ? static_cast<double>(vertices) / seconds_per_frame : 0.0; }
  double bytesPerSecond() const { return seconds_per_frame > 0.0 ? bytes_per_frame / seconds_per_frame : 0.0; }
  // vulkan: the same over the timestamp-query time, what the device's memory saw; 0 without one.
  double gpuBytesPerSecond() const { return gpu_seconds_per_frame > 0.0 ? bytes_per_frame / gpu_seconds_per_frame : 0.0; }
};

// The thesis's Table 6.3 columns for one fit, in seconds.
struct FitStageRecord {
  std::string dataset;
  std::size_t vertices = 0;
  std::size_t poses = 0;
  std::string rig;  // "auto" or "given"
  double rig_seconds = 0.0;
  double curve_identification = 0.0;
  double geometric_transform = 0.0;
  double fourier_and_deformation = 0.0;
  double analytic_solve = 0.0;
  double total = 0.0;

  double withoutRig() const { return curve_identification + geometric_transform + fourier_and_deformation + analytic_solve; }
};

struct BenchReport {
  std::string device;        // the Vulkan device's name, or "none (<reason>)"
  std::string cpu;           // /proc/cpuinfo model name
  unsigned hardware_threads = 0;
  std::string build;         // build type, compiler and flags
  std::string mesh;          // what was tiled
  bool quick = false;
  bool validation = false;   // the Khronos validation layer checked the Vulkan cases: its work is in their times
  std::string shader_inputs; // vulkan: "texel buffers" or "storage buffers" (host/shader_inputs.hpp); empty without
  // The Vulkan device's copy rates (device_bandwidth.hpp), vkCmdCopyBuffer's and the shader
  // copy's, each with the size of its buffers; 0 when not measured, and device_copy_note says why
  // when neither was. The Vulkan records are set against the faster.
  double buffer_copy_bytes = 0.0;
  double buffer_copy_bytes_per_second = 0.0;
  double shader_copy_bytes = 0.0;
  double shader_copy_bytes_per_second = 0.0;
  std::string device_copy_note;
  std::vector<BenchRecord> records;
  std::vector<FitStageRecord> fit_stages;

  double deviceCopyBytesPerSecond() const { return std::max(buffer_copy_bytes_per_second, shader_copy_bytes_per_second); }
  double deviceCopyBytes() const {
    return shader_copy_bytes_per_second > buffer_copy_bytes_per_second ? shader_copy_bytes : buffer_copy_bytes;
  }
};

// odeskin / lbs per-frame time of the same backend, threads and size; 0 when either is missing.
double odeskinOverLbs(const BenchReport& report, const BenchRecord& odeskin);
// The same from the timestamp-query times (vulkan): what the frame costs the GPU, without the
// submit-and-wait latency that dominates a real GPU's wall time at small sizes.
double gpuOdeskinOverLbs(const BenchReport& report, const BenchRecord& odeskin);

std::string toJson(const BenchReport& report);
std::string toCsv(const BenchReport& report);  // the records, one per line, with a header
// Atomic writes (temporary file + rename); kIoError naming the path.
Status writeJson(const std::filesystem::path& path, const BenchReport& report);
Status writeCsv(const std::filesystem::path& path, const BenchReport& report);

// The machine, build and compiler, for the report's header fields.
std::string cpuModelName();
std::string buildDescription();

}  // namespace odeskin::bench
