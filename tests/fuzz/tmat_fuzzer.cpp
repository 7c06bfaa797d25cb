// SPDX-License-Identifier: MIT
// libFuzzer target: the libigl .Tmat per-pose bone transform reader (engine/io/libigl_io.hpp). The
// first byte gives the bone count the caller expects (1 + byte % 32), the rest is the file; an
// accepted file gives that many rigid transforms with unit rotations.
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
  const std::string source = "fuzz.Tmat";
  const Result<std::vector<RigidTransform>> t = parseTmat(fuzz::text(data + 1, size - 1), source, bones);
  if (!fuzz::accepted(t, source)) return 0;
  fuzz::require(t->size() == bones, "accepted a file with another bone count");
  for (const RigidTransform& x : *t) {
    fuzz::require(std::abs(glm::length(x.rotation) - 1.0) < 1e-12, "a rotation is not a unit quaternion");
    fuzz::require(fuzz::finite(x.translation),
                  "a translation is not finite");
  }
  return 0;
}
