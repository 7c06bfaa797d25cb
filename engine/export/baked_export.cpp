// SPDX-License-Identifier: MIT
#include "baked_export.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "../core/number_text.hpp"
#include "../io/gltf_baked_writer.hpp"

namespace odeskin {
namespace {

// The frame times: f / fps up to the end, then the end itself. The count is checked in double before
// any time is stored: a huge segment length (or an end beyond double's range) would otherwise fill
// memory frame by frame, or loop forever, before the size check could refuse it.
Result<std::vector<double>> frameSeconds(double end_seconds, double fps, std::size_t vertices) {
  const double last = end_seconds * (1.0 - 1e-12);
  // The grid's count to within rounding; the exact count is checked again once it is known.
  ODESKIN_TRY(checkBakedSize(std::floor(last * fps) + 1.0, vertices));
  std::vector<double> seconds;
  for (std::size_t f = 0;; ++f) {
    const double s = static_cast<double>(f) / fps;
    if (s > last) break;
    seconds.push_back(s);
  }
  // The end is a frame too, unless the grid already stops within float32 reach of it.
  if (static_cast<float>(end_seconds) > static_cast<float>(seconds.back())) seconds.push_back(end_seconds);
  ODESKIN_TRY(checkBakedSize(seconds.size(), vertices));
  return seconds;
}

}  // namespace

Result<BakedExport> writeBakedExport(const DeformAsset& asset, const DeformPlayer& player, const std::filesystem::path& path,
                                     double fps, const std::string& generator,
                                     const std::function<void(std::string_view, double)>& progress,
                                     const gltf::MaterialLibrary* materials, bool quantize) {
  const double t_end = static_cast<double>(player.segmentCount());
  const double end_seconds = t_end * asset.segment_seconds;
  const std::size_t out_vertices = outputVertexCount(asset);
  Result<std::vector<double>> timed = frameSeconds(end_seconds, fps, out_vertices);
  if (!timed.ok()) {
    // Segments x segment length overflows double when the length is near its maximum.
    const std::string length = std::isfinite(end_seconds) ? numberText(end_seconds) + " s" : "beyond double's range";
    return Status(timed.status().code(), "export: " + timed.status().message() + " (" + length + " at " +
                                             numberText(fps) + " fps); lower --fps");
  }
  const std::vector<double>& seconds = *timed;
  std::vector<Vec3> positions(asset.vertexCount());
  std::vector<std::vector<Vec3>> frames, normals;
  frames.reserve(seconds.size());
  normals.reserve(seconds.size());
  for (std::size_t f = 0; f < seconds.size(); ++f) {
    const auto [segment, tau] = player.locate(seconds[f] / asset.segment_seconds);
    ODESKIN_TRY(player.play(asset, segment, tau, positions));
    frames.push_back(outputPositions(asset, positions));
    normals.push_back(outputNormals(asset, positions));
    if (progress) progress("bake", static_cast<double>(f + 1) / static_cast<double>(seconds.size()));
  }
  BakedGlbOptions options;
  options.linear = true;
  options.generator = generator;
  options.animation = "odeskin";
  options.materials = materials;
  options.quantize = quantize;
  BakedExport out{frames.size(), out_vertices, {}};
  ODESKIN_TRY(writeBakedGlb(path, outputFaces(asset), frames, seconds, options,
                            {normals, asset.render.uvs, asset.render.primitives}, &out.quantization));
  return out;
}

}  // namespace odeskin
