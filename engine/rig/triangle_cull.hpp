// SPDX-License-Identifier: MIT
// Which triangles a plane or a line through one point may meet, without looking at their corners.
// The centre section tries about 80 planes and 13 lines, each against thousands of triangles of
// which a few dozen matter, so this pass is most of its time. Each triangle is kept as a ball about
// its corners' mean (relative to the point), in float and in units of the largest such ball's reach,
// so that the test runs four triangles to an instruction; its margin is far above float rounding,
// so the lists are supersets of the triangles met, in ascending order, and the exact tests that
// follow give the same result as a test of every triangle.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "../core/types.hpp"

namespace odeskin {

class TriangleCull {
 public:
  TriangleCull() = default;
  // `middles[t]` relative to the point; `radii[t]` at least the distance of each corner from it.
  TriangleCull(const std::vector<Vec3>& middles, const std::vector<double>& radii);

  std::size_t size() const { return size_; }

  // The triangles a plane through the point with this unit normal may cut.
  void nearPlane(const Vec3& normal, std::vector<std::uint32_t>& out) const;
  // The triangles a line through the point along this unit direction may meet.
  void nearLine(const Vec3& direction, std::vector<std::uint32_t>& out) const;

 private:
  static constexpr std::size_t kBlock = 64;

  // Appends the indices of each block whose flags `flag(base, flags)` sets; a block with none is
  // skipped after one pass of the vectorised test, and within a block eight flags are read at once.
  template <class Flag>
  void collect(const Flag& flag, std::vector<std::uint32_t>& out) const {
    out.clear();
    alignas(8) std::array<std::uint8_t, kBlock> flags{};
    for (std::size_t base = 0; base < x_.size(); base += kBlock) {
      if (!flag(base, flags)) continue;
      for (std::size_t j = 0; j < kBlock; j += 8) {
        std::uint64_t word = 0;
        std::memcpy(&word, flags.data() + j, sizeof word);
        // Byte k of the block as the word's byte k from the low end, so the lowest bit set is the
        // lowest triangle.
        if constexpr (std::endian::native == std::endian::big) word = __builtin_bswap64(word);
        while (word != 0) {
          out.push_back(static_cast<std::uint32_t>(base + j + static_cast<std::size_t>(std::countr_zero(word)) / 8));
          word &= word - 1;
        }
      }
    }
  }

  std::size_t size_ = 0;
  bool keep_all_ = false;
  // Padded to whole blocks with triangles no plane or line meets (radius below zero).
  std::vector<float> x_, y_, z_, squared_length_, radius_, squared_radius_;
};

}  // namespace odeskin
