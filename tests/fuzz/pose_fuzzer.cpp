// SPDX-License-Identifier: MIT
// libFuzzer target: the libigl viewer's pose .json reader (engine/io/libigl_io.hpp), then forward
// kinematics on a chain of that many bones. The first byte gives the skeleton's bone count
// (1 + byte % 32), the rest is the file; an accepted pose has one unit rotation per bone, and
// posing the chain with it gives finite transforms.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/io/libigl_io.hpp"
#include "fuzz_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace odeskin;
  if (size == 0) return 0;
  const std::size_t bones = 1 + data[0] % 32;
  const std::string source = "fuzz.json";
  const Result<std::vector<glm::dquat>> q = parsePoseJson(fuzz::text(data + 1, size - 1), source, bones);
  if (!fuzz::accepted(q, source)) return 0;
  fuzz::require(q->size() == bones, "rotations for another bone count");
  for (const glm::dquat& r : *q) fuzz::require(std::abs(glm::length(r) - 1.0) < 1e-12, "not a unit quaternion");
  Skeleton chain;
  for (std::size_t b = 0; b < bones; ++b) {
    chain.heads.emplace_back(0.0, static_cast<double>(b), 0.0);
    chain.tails.emplace_back(0.0, static_cast<double>(b + 1), 0.0);
    chain.parents.push_back(static_cast<std::int32_t>(b) - 1);
    chain.names.push_back("bone" + std::to_string(b));
  }
  for (const RigidTransform& x : forwardKinematics(chain, *q)) {
    fuzz::require(std::abs(glm::length(x.rotation) - 1.0) < 1e-9, "forward kinematics lost unit length");
    fuzz::require(fuzz::finite(x.translation),
                  "forward kinematics gave a non-finite translation");
  }
  return 0;
}
