// SPDX-License-Identifier: MIT
// KHR_mesh_quantization for `odeskin export --quantize` (internal to the glTF writers). Positions
// become 16-bit signed grid coordinates centred on the base shape's box, morph-target POSITION
// deltas 16-bit integers in the same grid steps, NORMAL 8-bit and NORMAL deltas 16-bit normalized
// integers; a delta beyond 16 bits stays float32. The node that holds the mesh carries the grid:
// the baked mesh node, or for a skinned mesh, whose node's transform glTF ignores, the skeleton
// root (glb_assembly.hpp). Each attribute keeps the values it wrote, decoded, so that the writers
// can measure what quantization cost.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "../core/types.hpp"

namespace odeskin {

// The grid of the mesh's local space: position = origin + step * stored.
struct PositionGrid {
  Vec3 origin{0.0};
  double step = 1.0;

  Vec3 toGrid(const Vec3& position) const { return (position - origin) / step; }
};

// The box centre and longest side / 65534 of `positions`, so that every position is within
// +-32767 steps of the centre (step 1 for a single point).
PositionGrid positionGrid(std::span<const Vec3> positions);

// How a VEC3 attribute's components are stored.
enum class Vec3Encoding {
  kFloat,            // float32 (12 bytes)
  kShort,            // int16 integers (8 bytes with padding)
  kShortNormalized,  // int16 / 32767 (8 bytes with padding)
  kByteNormalized,   // int8 / 127 (4 bytes with padding)
};

// The encoding's value of `x` as stored and read back: rounded to its integers (clamped to their
// range), float32 for kFloat.
double encodedValue(Vec3Encoding encoding, double x);

// Whether every component of `values` (in the attribute's own units: grid steps, or a normal's
// [-1, 1]) fits the encoding without clamping.
bool fitsEncoding(Vec3Encoding encoding, std::span<const Vec3> values);

// 0, 1, ..., count - 1: the indices of a dense attribute.
std::vector<std::uint32_t> allVertexIndices(std::size_t count);

// A VEC3 accessor over the output's `count` vertices whose listed `indices` (increasing) hold
// `values` and the rest zero: dense with a 4-byte aligned stride, or sparse (tightly packed values,
// no bufferView for the zeros) when that takes fewer bytes. `bounds`: min/max, required of
// POSITION. `sparse` receives which; `decoded` (when given) the stored values read back, per index.
int appendVec3Accessor(tinygltf::Model& m, Vec3Encoding encoding, std::size_t count, std::vector<std::uint32_t> indices,
                       std::vector<Vec3> values, bool bounds, bool& sparse, std::vector<Vec3>* decoded = nullptr);

// What quantization cost a writer, in mesh units (zeros without it): the grid step, the largest
// position error the rounding makes where the file is exact (the compact export's weight keys, a
// bake's frames; glTF morphs before skinning, which moves an error rigidly, never enlarging it),
// the angles of the morphed normals from the exact ones there in degrees (99th percentile of the
// (vertex, key) pairs, and largest, found where the morphed normal nearly cancels), and the
// morph-target POSITION or NORMAL accessors that stay float32 because their deltas need more
// than 16 bits (grid steps, or a normal's [-1, 1]).
struct QuantizationCost {
  double step = 0.0;
  double position_error = 0.0;
  double normal_p99_degrees = 0.0;
  double normal_max_degrees = 0.0;
  std::size_t float_deltas = 0;
};

// Angles between exact and written normals, in degrees, gathered over vertices and times.
class NormalAngles {
 public:
  // A zero sum has no direction to keep (where the morphed normal cancels): skipped.
  void add(const Vec3& exact, const Vec3& written);
  double p99();  // 0 when none was added
  double largest() const;

 private:
  std::vector<double> degrees_;
};

}  // namespace odeskin
