// SPDX-License-Identifier: MIT
#include "gltf_quantized.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

#include "gltf_buffer_builder.hpp"

namespace odeskin {
namespace {

// int16 positions centred on the box: -32767 to 32767.
constexpr double kGridSteps = 65534.0;

struct Layout {
  int component_type;
  bool normalized;
  double scale;             // stored = round(value * scale) for integers
  double low, high;         // the integers' range
  std::size_t component_bytes;
  std::size_t stride;       // dense element, 4-byte aligned
};

Layout layoutOf(Vec3Encoding encoding) {
  switch (encoding) {
    case Vec3Encoding::kShort:
      return {TINYGLTF_COMPONENT_TYPE_SHORT, false, 1.0, -32768.0, 32767.0, 2, 8};
    case Vec3Encoding::kShortNormalized:
      return {TINYGLTF_COMPONENT_TYPE_SHORT, true, 32767.0, -32767.0, 32767.0, 2, 8};
    case Vec3Encoding::kByteNormalized:
      return {TINYGLTF_COMPONENT_TYPE_BYTE, true, 127.0, -127.0, 127.0, 1, 4};
    case Vec3Encoding::kFloat:
      break;
  }
  return {TINYGLTF_COMPONENT_TYPE_FLOAT, false, 1.0, 0.0, 0.0, 4, 12};
}

// The stored number of `x`: the integer, or the float32.
double storedNumber(const Layout& l, double x) {
  if (l.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT) return static_cast<float>(x);
  return std::clamp(std::round(x * l.scale), l.low, l.high);
}

// Elements of `values` one after another, each padded to `element_bytes`.
std::vector<unsigned char> packed(const Layout& l, std::span<const Vec3> values, std::size_t element_bytes) {
  std::vector<unsigned char> out(values.size() * element_bytes, 0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    unsigned char* at = out.data() + i * element_bytes;
    for (int k = 0; k < 3; ++k) {
      const double x = storedNumber(l, values[i][k]);
      unsigned char* c = at + static_cast<std::size_t>(k) * l.component_bytes;
      if (l.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        const auto f = static_cast<float>(x);
        std::memcpy(c, &f, sizeof f);
      } else if (l.component_bytes == 2) {
        const auto s = static_cast<std::int16_t>(x);
        std::memcpy(c, &s, sizeof s);
      } else {
        const auto b = static_cast<std::int8_t>(x);
        std::memcpy(c, &b, sizeof b);
      }
    }
  }
  return out;
}

void setStoredBounds(const Layout& l, tinygltf::Accessor& a, std::span<const Vec3> values, bool with_zero) {
  a.minValues.assign(3, with_zero ? 0.0 : std::numeric_limits<double>::infinity());
  a.maxValues.assign(3, with_zero ? 0.0 : -std::numeric_limits<double>::infinity());
  for (const Vec3& v : values) {
    for (int k = 0; k < 3; ++k) {
      double x = storedNumber(l, v[k]);
      if (l.normalized) x /= l.scale;  // normalized accessors' bounds are in decoded units
      a.minValues[static_cast<std::size_t>(k)] = std::min(a.minValues[static_cast<std::size_t>(k)], x);
      a.maxValues[static_cast<std::size_t>(k)] = std::max(a.maxValues[static_cast<std::size_t>(k)], x);
    }
  }
}

}  // namespace

PositionGrid positionGrid(std::span<const Vec3> positions) {
  PositionGrid grid;
  if (positions.empty()) return grid;
  Vec3 lo = positions.front();
  Vec3 hi = lo;
  for (const Vec3& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const Vec3 side = hi - lo;
  const double longest = std::max({side.x, side.y, side.z});
  grid.origin = 0.5 * (lo + hi);
  grid.step = longest > 0.0 ? longest / kGridSteps : 1.0;
  return grid;
}

double encodedValue(Vec3Encoding encoding, double x) {
  const Layout l = layoutOf(encoding);
  const double stored = storedNumber(l, x);
  return l.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ? stored : stored / l.scale;
}

bool fitsEncoding(Vec3Encoding encoding, std::span<const Vec3> values) {
  const Layout l = layoutOf(encoding);
  if (l.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT) return true;
  return std::all_of(values.begin(), values.end(), [&](const Vec3& v) {
    for (int k = 0; k < 3; ++k) {
      const double x = std::round(v[k] * l.scale);
      if (!(x >= l.low && x <= l.high)) return false;
    }
    return true;
  });
}

std::vector<std::uint32_t> allVertexIndices(std::size_t count) {
  std::vector<std::uint32_t> out(count);
  for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<std::uint32_t>(i);
  return out;
}

int appendVec3Accessor(tinygltf::Model& m, Vec3Encoding encoding, std::size_t count, std::vector<std::uint32_t> indices,
                       std::vector<Vec3> values, bool bounds, bool& sparse, std::vector<Vec3>* decoded) {
  const Layout l = layoutOf(encoding);
  if (indices.empty()) {  // a target that moves nothing still needs one sparse entry
    indices.push_back(0);
    values.assign(1, Vec3(0.0));
  }
  if (decoded != nullptr) {
    decoded->resize(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
      for (int k = 0; k < 3; ++k) (*decoded)[i][k] = encodedValue(encoding, values[i][k]);
    }
  }
  const std::size_t value_bytes = 3 * l.component_bytes;
  const std::size_t index_bytes = count <= 65536 ? 2 : 4;
  sparse = indices.size() * (index_bytes + value_bytes) < count * l.stride;
  tinygltf::Accessor a;
  a.componentType = l.component_type;
  a.normalized = l.normalized;
  a.type = TINYGLTF_TYPE_VEC3;
  a.count = count;
  if (!sparse) {
    std::vector<Vec3> dense(count, Vec3(0.0));
    for (std::size_t k = 0; k < indices.size(); ++k) dense[indices[k]] = values[k];
    const std::vector<unsigned char> bytes = packed(l, dense, l.stride);
    a.bufferView = gltf::appendView(m, bytes.data(), bytes.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
    if (l.stride != value_bytes) m.bufferViews[static_cast<std::size_t>(a.bufferView)].byteStride = l.stride;
    if (bounds) setStoredBounds(l, a, dense, false);
  } else {
    a.bufferView = -1;
    a.sparse.isSparse = true;
    a.sparse.count = static_cast<int>(indices.size());
    if (index_bytes == 2) {
      a.sparse.indices.bufferView = gltf::appendView(m, std::vector<std::uint16_t>(indices.begin(), indices.end()), 0);
      a.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    } else {
      a.sparse.indices.bufferView = gltf::appendView(m, indices, 0);
      a.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    }
    a.sparse.indices.byteOffset = 0;
    const std::vector<unsigned char> bytes = packed(l, values, value_bytes);
    a.sparse.values.bufferView = gltf::appendView(m, bytes.data(), bytes.size(), 0);
    a.sparse.values.byteOffset = 0;
    if (bounds) setStoredBounds(l, a, values, indices.size() < count);  // min/max after substitution
  }
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

void NormalAngles::add(const Vec3& exact, const Vec3& written) {
  const double a = glm::length(exact);
  const double b = glm::length(written);
  if (!(a > 0.0 && b > 0.0)) return;
  const double cosine = std::clamp(glm::dot(exact, written) / (a * b), -1.0, 1.0);
  degrees_.push_back(std::acos(cosine) * 180.0 / std::numbers::pi);
}

double NormalAngles::p99() {
  if (degrees_.empty()) return 0.0;
  const auto at = degrees_.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(degrees_.size() - 1));
  std::nth_element(degrees_.begin(), at, degrees_.end());
  return *at;
}

double NormalAngles::largest() const {
  return degrees_.empty() ? 0.0 : *std::max_element(degrees_.begin(), degrees_.end());
}

}  // namespace odeskin
