// SPDX-License-Identifier: MIT
// libFuzzer target: the glTF / GLB reader (engine/io/gltf_reader.hpp, through tinygltf) on
// arbitrary bytes, GLB or JSON by the first four bytes as for files. Each input is read three
// ways, since the request decides how far the reader goes: the bind mesh alone, poses at times
// (skin, animation channels and samplers), and morph target 0 as a pose.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/io/gltf_reader.hpp"
#include "fuzz_checks.hpp"

namespace {

using namespace odeskin;

void check(const std::string& bytes, const GltfPoseRequest& request) {
  const std::string source = "fuzz.gltf";
  const Result<ExampleSet> examples = parseGltfExamples(bytes, source, request);
  if (!fuzz::accepted(examples, source)) return;
  const std::size_t vertices = examples->rest_positions.size();
  for (const auto& pose : examples->poses) fuzz::require(pose.size() == vertices, "a pose of another vertex count");
  for (std::uint32_t v : examples->faces.indices) fuzz::require(v < vertices, "a face index out of range");
  for (std::uint32_t v : examples->render.topology_of_render) {
    fuzz::require(v < vertices, "a render vertex welded to no topology vertex");
  }
  for (std::uint32_t r : examples->render.faces.indices) {
    fuzz::require(r < examples->render.topology_of_render.size(), "a render face index out of range");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes = fuzz::text(data, size);
  GltfPoseRequest bind;
  bind.min_poses = 1;
  check(bytes, bind);
  GltfPoseRequest animated;
  animated.times = {0.0, 0.25, 1.0e6};
  check(bytes, animated);
  GltfPoseRequest morphed;
  morphed.morph_targets = {0};
  check(bytes, morphed);
  return 0;
}
