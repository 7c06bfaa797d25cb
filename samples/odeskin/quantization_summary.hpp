// SPDX-License-Identifier: MIT
// The summary line of a quantized glTF (export --quantize, play -o OUT.glb --quantize).
#pragma once

#include <ostream>
#include <string_view>

#include "engine/core/number_text.hpp"
#include "engine/io/gltf_quantized.hpp"

namespace odeskin {

// `cost`'s lengths as fractions of `box` (1 when they already are); `where`: where it was measured.
inline void printQuantization(std::ostream& out, const QuantizationCost& cost, double box, std::string_view where) {
  out << "quantized (KHR_mesh_quantization): grid step " << scientific(cost.step / box)
      << " of the box; rounding moves positions by at most " << scientific(cost.position_error / box)
      << " of the box at the " << where << "; normals: 99% within " << fixedText(cost.normal_p99_degrees, 2)
      << " degrees of the unrounded ones, at most " << fixedText(cost.normal_max_degrees, 1);
  if (cost.float_deltas > 0) out << "; " << cost.float_deltas << " morph-target attributes stay float32 (deltas beyond 16 bits)";
  out << "\n";
}

}  // namespace odeskin
