// SPDX-License-Identifier: MIT
#include "bench_report.hpp"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/io/obj_io.hpp"

#ifndef ODESKIN_BUILD_TYPE
#define ODESKIN_BUILD_TYPE "unknown"
#endif
#ifndef ODESKIN_CXX_FLAGS
#define ODESKIN_CXX_FLAGS ""
#endif

namespace odeskin::bench {

namespace {

double ratioToLbs(const BenchReport& report, const BenchRecord& odeskin, double BenchRecord::*seconds) {
  if (odeskin.*seconds <= 0.0) return 0.0;
  for (const BenchRecord& r : report.records) {
    if (r.kernel == "lbs" && r.backend == odeskin.backend && r.threads == odeskin.threads &&
        r.vertices == odeskin.vertices && r.*seconds > 0.0) {
      return odeskin.*seconds / r.*seconds;
    }
  }
  return 0.0;
}

}  // namespace

double odeskinOverLbs(const BenchReport& report, const BenchRecord& odeskin) {
  return ratioToLbs(report, odeskin, &BenchRecord::seconds_per_frame);
}

double gpuOdeskinOverLbs(const BenchReport& report, const BenchRecord& odeskin) {
  return ratioToLbs(report, odeskin, &BenchRecord::gpu_seconds_per_frame);
}

std::string toJson(const BenchReport& report) {
  nlohmann::ordered_json j;
  j["device"] = report.device;
  j["machine"] = {{"cpu", report.cpu}, {"hardware_threads", report.hardware_threads}};
  j["build"] = report.build;
  j["mesh"] = report.mesh;
  j["quick"] = report.quick;
  j["validation"] = report.validation;
  if (!report.shader_inputs.empty()) j["shader_inputs"] = report.shader_inputs;
  if (report.deviceCopyBytesPerSecond() > 0.0) {
    j["device_copy"] = {{"bytes", report.deviceCopyBytes()},
                        {"bytes_per_second", report.deviceCopyBytesPerSecond()},
                        {"buffer_copy_bytes_per_second", report.buffer_copy_bytes_per_second},
                        {"shader_copy_bytes_per_second", report.shader_copy_bytes_per_second}};
  } else {
    j["device_copy"] = {{"note", report.device_copy_note}};
  }
  j["records"] = nlohmann::ordered_json::array();
  for (const BenchRecord& r : report.records) {
    nlohmann::ordered_json e;
    e["case"] = r.kernel;
    e["backend"] = r.backend;
    e["threads"] = r.threads;
    e["vertices"] = r.vertices;
    e["terms"] = r.terms;
    e["seconds_per_frame"] = r.seconds_per_frame;
    e["vertices_per_second"] = r.verticesPerSecond();
    if (r.backend == "vulkan") e["gpu_seconds_per_frame"] = r.gpu_seconds_per_frame;
    e["upload_seconds"] = r.upload_seconds;
    e["frames"] = r.frames;
    e["max_error"] = r.max_error;
    e["bytes_per_frame"] = r.bytes_per_frame;
    e["bytes_per_second"] = r.bytesPerSecond();
    if (r.backend == "vulkan") e["gpu_bytes_per_second"] = r.gpuBytesPerSecond();
    if (r.kernel == "odeskin") {
      const double ratio = odeskinOverLbs(report, r);
      if (ratio > 0.0) e["odeskin_over_lbs"] = ratio;
      const double gpu_ratio = gpuOdeskinOverLbs(report, r);
      if (gpu_ratio > 0.0) e["gpu_odeskin_over_lbs"] = gpu_ratio;
      if (r.paired_over_lbs > 0.0) e["paired_odeskin_over_lbs"] = r.paired_over_lbs;
      if (r.paired_gpu_over_lbs > 0.0) e["paired_gpu_odeskin_over_lbs"] = r.paired_gpu_over_lbs;
    }
    j["records"].push_back(std::move(e));
  }
  j["fit_stages"] = nlohmann::ordered_json::array();
  for (const FitStageRecord& f : report.fit_stages) {
    j["fit_stages"].push_back({{"dataset", f.dataset},
                               {"vertices", f.vertices},
                               {"poses", f.poses},
                               {"rig", f.rig},
                               {"rig_seconds", f.rig_seconds},
                               {"curve_identification", f.curve_identification},
                               {"geometric_transform", f.geometric_transform},
                               {"fourier_and_deformation", f.fourier_and_deformation},
                               {"analytic_solve", f.analytic_solve},
                               {"total_without_rig", f.withoutRig()},
                               {"total", f.total}});
  }
  return j.dump(2) + "\n";
}

std::string toCsv(const BenchReport& report) {
  std::ostringstream out;
  out.precision(9);
  out << "case,backend,threads,vertices,terms,seconds_per_frame,vertices_per_second,gpu_seconds_per_frame,"
         "upload_seconds,frames,max_error,odeskin_over_lbs,bytes_per_frame,bytes_per_second,gpu_odeskin_over_lbs,"
         "paired_odeskin_over_lbs,paired_gpu_odeskin_over_lbs\n";
  for (const BenchRecord& r : report.records) {
    out << r.kernel << ',' << r.backend << ',' << r.threads << ',' << r.vertices << ',' << r.terms << ','
        << r.seconds_per_frame << ',' << r.verticesPerSecond() << ',' << r.gpu_seconds_per_frame << ','
        << r.upload_seconds << ',' << r.frames << ',' << r.max_error << ',';
    if (r.kernel == "odeskin") out << odeskinOverLbs(report, r);
    out << ',' << r.bytes_per_frame << ',' << r.bytesPerSecond() << ',';
    if (r.kernel == "odeskin") out << gpuOdeskinOverLbs(report, r);
    out << ',';
    if (r.paired_over_lbs > 0.0) out << r.paired_over_lbs;
    out << ',';
    if (r.paired_gpu_over_lbs > 0.0) out << r.paired_gpu_over_lbs;
    out << '\n';
  }
  return out.str();
}

Status writeJson(const std::filesystem::path& path, const BenchReport& report) {
  return writeFileAtomically(path, toJson(report));
}

Status writeCsv(const std::filesystem::path& path, const BenchReport& report) {
  return writeFileAtomically(path, toCsv(report));
}

std::string cpuModelName() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "unknown";
}

std::string buildDescription() {
  std::string compiler = "unknown compiler";
#if defined(__clang__)
  compiler = "clang " __clang_version__;
#elif defined(__GNUC__)
  compiler = "gcc " __VERSION__;
#endif
  return std::string(ODESKIN_BUILD_TYPE) + ", " + compiler + ", flags: " + ODESKIN_CXX_FLAGS;
}

}  // namespace odeskin::bench
