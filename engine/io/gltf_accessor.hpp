// SPDX-License-Identifier: MIT
// glTF accessor decoding (internal to odeskin_gltf). tinygltf parses accessors but leaves the rest to
// us: `normalized` is only a flag, byteStride 0 means tightly packed, sparse substitutions are not
// applied and nothing is bounds-checked. readAccessor does all of that (glTF 2.0 spec 3.6.2 and
// 3.11, "Accessors" and "Animations": normalized integer decoding).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "../core/result.hpp"

namespace odeskin::gltf {

// One storage format a caller accepts: a component type and the accessor's `normalized` flag.
struct AccessorFormat {
  int component_type = TINYGLTF_COMPONENT_TYPE_FLOAT;  // TINYGLTF_COMPONENT_TYPE_*
  bool normalized = false;
};

inline constexpr AccessorFormat kFloat{TINYGLTF_COMPONENT_TYPE_FLOAT, false};
inline constexpr AccessorFormat kUByte{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, false};
inline constexpr AccessorFormat kUShort{TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, false};
inline constexpr AccessorFormat kUInt{TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, false};
inline constexpr AccessorFormat kByte{TINYGLTF_COMPONENT_TYPE_BYTE, false};
inline constexpr AccessorFormat kShort{TINYGLTF_COMPONENT_TYPE_SHORT, false};
inline constexpr AccessorFormat kUByteNorm{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, true};
inline constexpr AccessorFormat kUShortNorm{TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, true};
inline constexpr AccessorFormat kByteNorm{TINYGLTF_COMPONENT_TYPE_BYTE, true};
inline constexpr AccessorFormat kShortNorm{TINYGLTF_COMPONENT_TYPE_SHORT, true};

// What the caller expects of an accessor; anything else is a kParseError naming the accessor.
struct AccessorRequest {
  std::string what;                         // its role, for messages: "POSITION of primitive 0"
  int type = TINYGLTF_TYPE_SCALAR;          // TINYGLTF_TYPE_*
  std::span<const AccessorFormat> formats;  // accepted storage formats
  std::size_t count = 0;                    // required element count; 0: any
};

// Decoded values in double precision: count x components, element-major; a matrix element is
// column-major like glTF (its column padding removed).
struct AccessorData {
  std::size_t count = 0;
  std::size_t components = 0;
  std::vector<double> values;

  double at(std::size_t element, std::size_t component) const { return values[element * components + component]; }
};

// The values one read of a file may decode, summed over every accessor it reads and every morph
// target it fills with zeros. Each accessor alone is bounded by the bytes behind it, but accessors
// may share those bytes, and primitives, morph targets and animation channels may repeat them, so a
// file of a few kilobytes could otherwise ask for gigabytes. The total may reach kValuesPerByte per
// byte of the file's buffers (as stored: compressed bufferViews count at their compressed size),
// and kMinValues in any case: a file that reads each byte once stays far inside it, even when
// dozens of primitives share one vertex buffer.
class DecodeBudget {
 public:
  static constexpr std::size_t kValuesPerByte = 32;
  static constexpr std::size_t kMinValues = std::size_t{1} << 24;  // 128 MiB as doubles

  explicit DecodeBudget(const tinygltf::Model& model);
  // Counts `values` more; kParseError naming `what` if the total would pass the limit.
  Status charge(std::size_t values, const std::string& what);

 private:
  std::size_t limit_ = 0;
  std::size_t spent_ = 0;
};

// Decodes accessor `index`: base data through its bufferView (byteOffset, byteStride; zeros when it
// has none), normalized integers mapped to [0, 1] or [-1, 1] as the spec says, then the sparse
// substitutions on top. kParseError naming the accessor index and its role: index out of range, a
// type or format the request does not accept, a count other than the required one, a bufferView or
// buffer out of range, data past the end of its bufferView or buffer, a byteStride smaller than an
// element, non-finite floats, sparse indices not strictly increasing or >= count, a count without
// a bufferView above one element per byte of the file's buffers (at least 65536; at most 2^27 values),
// or more values than are left in `budget` (charged with the decoded values).
Result<AccessorData> readAccessor(const tinygltf::Model& model, int index, const AccessorRequest& request,
                                  DecodeBudget& budget);

}  // namespace odeskin::gltf
