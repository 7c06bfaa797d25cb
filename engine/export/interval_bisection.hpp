// SPDX-License-Identifier: MIT
// Adaptive key placement shared by the weight and skeleton keys: an interval between two keys is
// halved until its interpolant is accurate enough or the halves would get narrower than a gap.
#pragma once

#include <vector>

namespace odeskin {

// Appends to (taus, keys) the right end of every accepted sub-interval of [a, b], in order. An
// interval is halved while too_coarse(a, ka, b, kb) holds and both halves stay at least min_gap
// wide; key_at(tau) evaluates the key at a new midpoint.
template <typename Key, typename KeyAt, typename TooCoarse>
void bisectInterval(double a, const Key& ka, double b, const Key& kb, double min_gap, const KeyAt& key_at,
                    const TooCoarse& too_coarse, std::vector<double>& taus, std::vector<Key>& keys) {
  if (b - a >= 2.0 * min_gap && too_coarse(a, ka, b, kb)) {
    const double mid = 0.5 * (a + b);
    const Key km = key_at(mid);
    bisectInterval(a, ka, mid, km, min_gap, key_at, too_coarse, taus, keys);
    bisectInterval(mid, km, b, kb, min_gap, key_at, too_coarse, taus, keys);
    return;
  }
  taus.push_back(b);
  keys.push_back(kb);
}

}  // namespace odeskin
