// SPDX-License-Identifier: MIT
// libFuzzer target: the fitting pipeline (engine/pipeline/fit_pipeline.hpp) as `odeskin fit` runs
// it on OBJ poses, on any mesh the OBJ reader and the sequence's manifold check accept. The second
// pose bends the mesh: the half beyond the middle of its longest box side turns by half a radian
// about an axis across that side; a third pose, when there is one, turns it half as far (two
// segments, the second starting with the rates the first carries in). Bits of the input's last
// byte pick the rig (motion or iso-curves), the material, the residual space, the skinning and the
// third pose, so one corpus reaches every path. A mesh must give an asset that keeps its promises
// or a Status, never a crash:
//  - a refusal is not an internal error;
//  - an accepted asset validates, reproduces every pose within the key tolerance (the sparse
//    remainders' promise), plays a frame inside each segment with finite positions, and survives
//    its file: it encodes as `odeskin fit -o` saves it, decodes, and encodes again to the same
//    bytes.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "engine/io/asset_file.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/mesh/poly_mesh.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "fuzz_checks.hpp"

namespace {

using namespace odeskin;

// The fit costs far more per vertex than a reader, mostly in the motion rig: in CI's -O0 build
// the 420-vertex cylinder took 6.85 s as one input (libFuzzer's leak check included) and a
// 594-vertex mesh 11.4 s, over the 10 s an input may take. Larger meshes add no new shapes.
constexpr std::size_t kMaxVertices = 300;
// A third pose makes the motion rig about twice as slow (-O0: 5.3 s against 2.8 s for a
// 194-vertex tube), so only meshes up to this size get one.
constexpr std::size_t kMaxVerticesThreePoses = 160;
constexpr double kBendRadians = 0.5;
// Rounding between the fit's own playback and the tolerance test (relative).
constexpr double kToleranceSlack = 1e-9;

std::vector<Vec3> bent(const std::vector<Vec3>& rest, double radians) {
  Vec3 lo = rest.front(), hi = rest.front();
  for (const Vec3& p : rest) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const Vec3 extent = hi - lo;
  const int along = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  Vec3 axis(0.0);
  axis[(along + 1) % 3] = 1.0;
  const Vec3 centre = 0.5 * (lo + hi);
  const glm::dquat turn = glm::angleAxis(radians, axis);
  std::vector<Vec3> out = rest;
  for (Vec3& p : out) {
    if (p[along] > centre[along]) p = centre + turn * (p - centre);
  }
  return out;
}

PipelineOptions optionsFrom(std::uint8_t bits) {
  PipelineOptions options;
  options.modes = 5;  // any N exercises the same code; fewer keep inputs fast
  options.curve_rig = (bits & 1) != 0;
  options.material = (bits & 2) != 0 ? skinMaterial() : staticMaterial();
  options.residual_space = (bits & 4) != 0 ? ResidualSpace::kPosed : ResidualSpace::kBind;
  options.skinning = (bits & 8) != 0 ? SkinningMode::kDualQuaternion : SkinningMode::kLinear;
  return options;
}

void checkAsset(const PipelineResult& fit, const PipelineOptions& options, std::size_t vertices, std::size_t poses) {
  const DeformAsset& asset = fit.asset;
  const Status valid = validateDeformAsset(asset);
  fuzz::require(valid.ok(), "fit: the asset does not validate: " + valid.toString());
  fuzz::require(asset.vertexCount() == vertices, "fit: the asset lost vertices");
  fuzz::require(fit.report.key_error.size() == poses, "fit: not one key error per pose");
  for (const double e : fit.report.key_error) {
    fuzz::require(std::isfinite(e) && e <= options.key_tolerance * (1.0 + kToleranceSlack),
                  "fit: a key pose is not reproduced within the key tolerance: " + std::to_string(e));
  }
  const Result<DeformPlayer> player = DeformPlayer::create(asset);
  fuzz::require(player.ok(), "fit: the asset does not play: " + player.status().toString());
  std::vector<Vec3> frame(vertices);
  for (std::uint32_t segment = 0; segment + 1 < poses; ++segment) {
    const Status played = player->play(asset, segment, 0.5, frame);
    fuzz::require(played.ok(), "fit: a frame between the keys fails: " + played.toString());
    fuzz::require(std::all_of(frame.begin(), frame.end(), fuzz::finite), "fit: a frame between the keys is not finite");
  }
  const Result<std::string> bytes = encodeAsset(asset);
  fuzz::require(bytes.ok(), "fit: the asset does not encode: " + bytes.status().toString());
  const Result<DeformAsset> decoded = decodeAsset(*bytes, "fit.odsk");
  fuzz::require(decoded.ok(), "fit: the saved asset does not decode: " + decoded.status().toString());
  const Result<std::string> again = encodeAsset(*decoded);
  fuzz::require(again.ok() && *again == *bytes, "fit: the decoded asset encodes to other bytes");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string source = "fuzz.obj";
  const Result<ObjMesh> mesh = parseObj(fuzz::text(data, size), source);
  if (!mesh.ok() || mesh->positions.size() > kMaxVertices) return 0;
  // `odeskin fit` reads OBJ poses through readObjSequence, which refuses a non-manifold face list.
  if (!fuzz::accepted(buildPolyMesh(mesh->positions, mesh->faces, source), source)) return 0;
  ExampleSet examples;
  examples.rest_positions = mesh->positions;
  examples.faces = mesh->faces;
  examples.poses = {mesh->positions, bent(mesh->positions, kBendRadians)};
  examples.pose_labels = {"rest.obj", "bent.obj"};
  const std::uint8_t bits = data[size - 1];
  if ((bits & 16) != 0 && mesh->positions.size() <= kMaxVerticesThreePoses) {
    examples.poses.push_back(bent(mesh->positions, 0.5 * kBendRadians));
    examples.pose_labels.emplace_back("half.obj");
  }
  const PipelineOptions options = optionsFrom(bits);
  const Result<PipelineResult> fit = runFitPipeline(examples, options);
  if (!fit.ok()) {
    fuzz::require(fit.status().code() != StatusCode::kInternal, "a mesh refused as an internal error: " + fit.status().toString());
    return 0;
  }
  checkAsset(*fit, options, mesh->positions.size(), examples.poses.size());
  return 0;
}
