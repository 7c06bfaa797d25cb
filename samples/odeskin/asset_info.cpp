// SPDX-License-Identifier: MIT
#include "asset_info.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <set>
#include <string>
#include <system_error>

#include "engine/core/number_text.hpp"
#include "engine/core/smoothing_groups.hpp"
#include "engine/io/asset_file.hpp"
#include "engine/kernels/fourier_deform_job.hpp"

namespace odeskin {
namespace {

constexpr std::size_t kFloatBytes = 4;

std::string bytesText(std::uintmax_t bytes) {
  char text[64];
  if (bytes < std::uintmax_t{10} * 1024) {
    std::snprintf(text, sizeof text, "%ju B", bytes);
  } else if (bytes < std::uintmax_t{10} * 1024 * 1024) {
    std::snprintf(text, sizeof text, "%ju B (%.1f KiB)", bytes, static_cast<double>(bytes) / 1024.0);
  } else {
    std::snprintf(text, sizeof text, "%ju B (%.1f MiB)", bytes, static_cast<double>(bytes) / (1024.0 * 1024.0));
  }
  return text;
}

// Sizes and counts of the bake, which a huge segment length takes past std::size_t (or past
// double's range, to infinity): integers while double holds them exactly, numbers beyond.
constexpr double kExactInDouble = 9007199254740992.0;  // 2^53

std::string bytesText(double bytes) {
  if (bytes < kExactInDouble) return bytesText(static_cast<std::uintmax_t>(bytes));
  return numberText(bytes) + " B";
}

std::string countText(double count) {
  if (count < kExactInDouble) return std::to_string(static_cast<std::uint64_t>(count));
  return numberText(count);
}

// Segments x segment length overflows double when both are huge.
std::string secondsText(double seconds) {
  if (std::isfinite(seconds)) return numberText(seconds);
  return "more than " + numberText(std::numeric_limits<double>::max());
}

std::string ratioText(double ratio) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", ratio);
  return text;
}

}  // namespace

AssetStats assetStats(const DeformAsset& asset, std::uintmax_t file_bytes) {
  AssetStats s;
  s.vertices = asset.vertexCount();
  s.render_vertices = outputVertexCount(asset);
  s.faces = outputFaces(asset).faceCount();
  if (!asset.render.normals.empty()) {
    s.hard_edge_vertices = smoothingGroups(asset.render.topology_of_render, asset.vertexCount(), asset.render.normals).hard_vertices;
  }
  s.texcoords = !asset.render.uvs.empty();
  s.obj_layout = asset.render.obj_order;
  s.primitives = asset.render.primitives.size();
  s.curves = asset.curveCount();
  std::set<std::uint32_t> parts;
  for (const IsoCurve& curve : asset.curves) parts.insert(curve.part);
  s.parts = parts.size();
  s.terms = asset.modes;
  s.key_poses = asset.key_poses.size();
  s.segments = asset.segments.size();
  s.bones = asset.bone_count;
  s.materials = asset.materials.size();
  s.seconds = static_cast<double>(s.segments) * asset.segment_seconds;
  s.coefficient_floats = s.segments * s.curves * coefficientsPerCurve(asset.modes) * 3;
  for (const DeformSegment& seg : asset.segments) s.remainders += seg.remainders.size();
  s.file_bytes = file_bytes;
  Result<PackedDeformData> packed = packDeformAsset(asset);
  s.gpu_bytes = packed.ok() ? packed->byteSize() : 0;
  s.pose_bytes = s.key_poses * s.vertices * 3 * kFloatBytes;
  s.baked_frames = std::round(s.seconds * kBakedFps) + 1.0;
  s.baked_bytes = s.baked_frames * static_cast<double>(s.vertices * 3 * kFloatBytes);
  s.ratio_to_poses = s.pose_bytes > 0 ? static_cast<double>(file_bytes) / static_cast<double>(s.pose_bytes) : 0.0;
  s.ratio_to_baked = s.baked_bytes > 0.0 ? static_cast<double>(file_bytes) / s.baked_bytes : 0.0;
  return s;
}

void printAssetStats(std::ostream& out, const std::filesystem::path& path, const AssetStats& s) {
  out << "asset:          " << path.string() << "\n";
  out << "vertices:       " << s.vertices;
  if (s.render_vertices != s.vertices) {
    out << " (" << s.render_vertices << " render vertices";
    if (s.hard_edge_vertices > 0) out << ", " << s.hard_edge_vertices << " on hard edges";
    out << ")";
  }
  if (s.texcoords) out << (s.obj_layout ? "; with the input's texture coordinates (vt)" : "; with the input's TEXCOORD_0");
  if (s.primitives > 0) out << "; " << s.primitives << " glTF primitive" << (s.primitives == 1 ? "" : "s") << " with their materials";
  out << "\nfaces:          " << s.faces << "\n";
  out << "curves:         " << s.curves << "\n";
  out << "parts:          " << s.parts << (s.curves > 0 && s.parts == 0 ? " (curves not stored)" : "") << "\n";
  out << "terms N:        " << s.terms << " (" << coefficientsPerCurve(s.terms) << " coefficients per curve)\n";
  out << "key poses:      " << s.key_poses << " (" << s.segments << " segment" << (s.segments == 1 ? "" : "s") << ", "
      << secondsText(s.seconds) << " s)\n";
  out << "bones:          " << s.bones << "\n";
  out << "materials:      " << s.materials << "\n";
  out << "coefficients:   " << s.coefficient_floats << " floats (segments x curves x (2N+2) x 3)\n";
  out << "remainders:     " << s.remainders << "\n";
  out << "file bytes:     " << bytesText(s.file_bytes) << "\n";
  out << "GPU bytes:      " << bytesText(s.gpu_bytes) << "\n";
  out << "every pose:     " << bytesText(s.pose_bytes) << " (K x V x 3 float32); asset / that = "
      << ratioText(s.ratio_to_poses) << "\n";
  if (!std::isfinite(s.baked_frames)) {
    out << "baked 30 fps:   more frames than a double can count (the playback length overflows)\n";
    return;
  }
  out << "baked 30 fps:   " << bytesText(s.baked_bytes) << " (" << countText(s.baked_frames)
      << " frames x V x 3 float32); asset / that = " << ratioText(s.ratio_to_baked) << "\n";
}

int runInfoCommand(const std::filesystem::path& path, Console& console) {
  Result<DeformAsset> asset = loadAsset(path);
  if (!asset.ok()) return reportFailure(console, asset.status());
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec) return reportFailure(console, ioError(path.string() + ": " + ec.message()));
  printAssetStats(console.out, path, assetStats(*asset, bytes));
  return kExitOk;
}

}  // namespace odeskin
