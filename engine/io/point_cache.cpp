// SPDX-License-Identifier: MIT
#include "point_cache.hpp"

#include <bit>
#include <cmath>
#include <limits>

#include "../core/number_text.hpp"
#include "little_endian.hpp"
#include "obj_io.hpp"

namespace odeskin {
namespace {

constexpr char kPc2Signature[12] = "POINTCACHE2";  // with its terminating zero: 12 bytes
constexpr std::uint32_t kPc2Version = 1;
constexpr double kFloatMax = std::numeric_limits<float>::max();

// MDD is big-endian whatever the machine writing it.
void appendBigEndianU32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((v >> shift) & 0xFFU));
}

void appendF32(std::string& out, float v, PointCacheFormat format) {
  const auto bits = std::bit_cast<std::uint32_t>(v);
  format == PointCacheFormat::kMdd ? appendBigEndianU32(out, bits) : appendLittleEndianU32(out, bits);
}

}  // namespace

std::string pointCacheSizeProblem(std::size_t samples, std::size_t vertices) {
  if (vertices == 0) return "a point cache needs at least one vertex";
  if (samples == 0) return "a point cache needs at least one frame";
  const long double bytes = static_cast<long double>(samples) * static_cast<long double>(vertices) * 12.0L;
  if (bytes > static_cast<long double>(kMaxPointCacheDataBytes)) {
    return std::to_string(samples) + " frames of " + std::to_string(vertices) + " vertices need " +
           numberText(static_cast<double>(bytes / (1024.0L * 1024.0L * 1024.0L))) +
           " GiB, over the 4 GiB one point cache holds";
  }
  return {};
}

PointCacheBuilder::PointCacheBuilder(PointCacheFormat format, std::size_t vertices, std::size_t samples)
    : format_(format), vertices_(vertices) {
  // Room for the header too, so that write() inserts it without taking the memory again.
  if (pointCacheSizeProblem(samples, vertices).empty()) data_.reserve(kPc2HeaderBytes + 4 * samples + samples * vertices * 12);
}

Status PointCacheBuilder::add(std::span<const Vec3> positions) {
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
      appendF32(data_, static_cast<float>(x), format_);
    }
  }
  ++samples_;
  return okStatus();
}

Status PointCacheBuilder::write(const std::filesystem::path& path, const PointCacheTiming& timing) {
  const std::string where = path.string() + ": ";
  if (const std::string problem = pointCacheSizeProblem(samples_, vertices_); !problem.empty()) {
    return invalidArgument(where + problem);
  }
  if (!(timing.fps > 0.0 && timing.fps <= kFloatMax)) {
    return invalidArgument(where + "frames per second must be positive, got " + messageNumber(timing.fps));
  }
  const double last_frame = timing.start_frame + static_cast<double>(samples_);
  if (!(std::abs(timing.start_frame) <= kFloatMax)) {
    return invalidArgument(where + "the first frame " + messageNumber(timing.start_frame) + " is not a float32 number");
  }
  if (!(std::abs(last_frame / timing.fps) <= kFloatMax)) {
    return invalidArgument(where + "frame " + messageNumber(last_frame) + " at " + messageNumber(timing.fps) +
                           " frames per second lies at a time past float32's range");
  }
  std::string header;
  if (format_ == PointCacheFormat::kPc2) {
    header.assign(kPc2Signature, sizeof kPc2Signature);
    appendLittleEndianU32(header, kPc2Version);
    appendLittleEndianU32(header, static_cast<std::uint32_t>(vertices_));
    appendLittleEndianF32(header, static_cast<float>(timing.start_frame));
    appendLittleEndianF32(header, 1.0F);  // one scene frame per sample
    appendLittleEndianU32(header, static_cast<std::uint32_t>(samples_));
  } else {
    appendBigEndianU32(header, static_cast<std::uint32_t>(samples_));
    appendBigEndianU32(header, static_cast<std::uint32_t>(vertices_));
    for (std::size_t k = 0; k < samples_; ++k) {
      appendF32(header, static_cast<float>((timing.start_frame + static_cast<double>(k)) / timing.fps), format_);
    }
  }
  // Inserted in place (the constructor reserved room) and taken out again, so a cache of
  // gigabytes is never copied whole and write() can be called again.
  data_.insert(0, header);
  Status written = writeFileAtomically(path, data_);
  data_.erase(0, header.size());
  return written;
}

}  // namespace odeskin
