// SPDX-License-Identifier: MIT
#include "point_cache.hpp"

#include <cmath>
#include <limits>

#include "../core/number_text.hpp"
#include "little_endian.hpp"
#include "obj_io.hpp"

namespace odeskin {
namespace {

constexpr char kSignature[12] = "POINTCACHE2";  // with its terminating zero: 12 bytes
constexpr std::uint32_t kVersion = 1;
constexpr double kFloatMax = std::numeric_limits<float>::max();

}  // namespace

std::string pc2SizeProblem(std::size_t samples, std::size_t vertices) {
  if (vertices == 0) return "a point cache needs at least one vertex";
  if (samples == 0) return "a point cache needs at least one frame";
  const long double bytes = static_cast<long double>(samples) * static_cast<long double>(vertices) * 12.0L;
  if (bytes > static_cast<long double>(kMaxPc2DataBytes)) {
    return std::to_string(samples) + " frames of " + std::to_string(vertices) + " vertices need " +
           numberText(static_cast<double>(bytes / (1024.0L * 1024.0L * 1024.0L))) +
           " GiB, over the 4 GiB one point cache holds";
  }
  return {};
}

Pc2Builder::Pc2Builder(std::size_t vertices, std::size_t samples) : vertices_(vertices) {
  if (pc2SizeProblem(samples, vertices).empty()) data_.reserve(kPc2HeaderBytes + samples * vertices * 12);
  data_.resize(kPc2HeaderBytes);  // write() fills it in
}

Status Pc2Builder::add(std::span<const Vec3> positions) {
  if (positions.size() != vertices_) {
    return invalidArgument("point cache frame " + std::to_string(samples_) + " has " +
                           std::to_string(positions.size()) + " vertices, the cache " + std::to_string(vertices_));
  }
  const std::size_t start = data_.size();
  for (std::size_t v = 0; v < positions.size(); ++v) {
    for (int axis = 0; axis < 3; ++axis) {
      const double x = positions[v][axis];
      if (!(std::abs(x) <= kFloatMax)) {
        data_.resize(start);
        return invalidArgument("point cache frame " + std::to_string(samples_) + ", vertex " + std::to_string(v) +
                               ": " + messageNumber(x) + " is not a finite float32 coordinate");
      }
      appendLittleEndianF32(data_, static_cast<float>(x));
    }
  }
  ++samples_;
  return okStatus();
}

Status Pc2Builder::write(const std::filesystem::path& path, double start_frame, double sample_frames) {
  const std::string where = path.string() + ": ";
  if (const std::string problem = pc2SizeProblem(samples_, vertices_); !problem.empty()) {
    return invalidArgument(where + problem);
  }
  if (!(std::abs(start_frame) <= kFloatMax)) {
    return invalidArgument(where + "the first frame " + messageNumber(start_frame) + " is not a float32 number");
  }
  if (!(sample_frames > 0.0 && sample_frames <= kFloatMax)) {
    return invalidArgument(where + "frames per sample must be positive, got " + messageNumber(sample_frames));
  }
  // The header is built apart and copied over the body's reserved first bytes, so a cache of
  // gigabytes is never copied whole.
  std::string header(kSignature, sizeof kSignature);
  appendLittleEndianU32(header, kVersion);
  appendLittleEndianU32(header, static_cast<std::uint32_t>(vertices_));
  appendLittleEndianF32(header, static_cast<float>(start_frame));
  appendLittleEndianF32(header, static_cast<float>(sample_frames));
  appendLittleEndianU32(header, static_cast<std::uint32_t>(samples_));
  data_.replace(0, kPc2HeaderBytes, header);
  return writeFileAtomically(path, data_);
}

}  // namespace odeskin
