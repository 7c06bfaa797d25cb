// SPDX-License-Identifier: MIT
// libFuzzer target: the libigl .tgf skeleton reader (engine/io/libigl_io.hpp) on arbitrary bytes;
// an accepted skeleton must be one forward kinematics can pose.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/io/libigl_io.hpp"
#include "fuzz_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace odeskin;
  const std::string source = "fuzz.tgf";
  const Result<Skeleton> skeleton = parseTgf(fuzz::text(data, size), source);
  if (!fuzz::accepted(skeleton, source)) return 0;
  const std::size_t bones = skeleton->boneCount();
  fuzz::require(bones > 0, "accepted a skeleton without bones");
  fuzz::require(skeleton->parents.size() == bones && skeleton->heads.size() == bones && skeleton->tails.size() == bones &&
                    skeleton->names.size() == bones,
                "skeleton arrays of different lengths");
  for (std::size_t b = 0; b < bones; ++b) {
    const std::int32_t p = skeleton->parents[b];
    fuzz::require(p >= -1 && p < static_cast<std::int64_t>(bones), "parent out of range");
    std::size_t steps = 0;
    for (std::int32_t q = p; q >= 0; q = skeleton->parents[static_cast<std::size_t>(q)]) {
      fuzz::require(++steps <= bones, "accepted a cycle of parents");
    }
  }
  fuzz::require(forwardKinematics(*skeleton, {}).size() == bones, "forward kinematics lost bones");
  return 0;
}
