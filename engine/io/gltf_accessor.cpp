// SPDX-License-Identifier: MIT
#include "gltf_accessor.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "gltf_meshopt.hpp"

namespace odeskin::gltf {
namespace {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian; so is memcpy here");

// An accessor without a bufferView is zeros (plus sparse values): nothing in the file bounds its
// count, so cap what we allocate for one (2^27 doubles = 1 GiB) and, tighter, allow it no more
// elements than a backed accessor of the same file could have (one per byte of its buffers, and at
// least kMinUnbackedCount): else a few hundred bytes could declare gigabytes of zeros.
constexpr std::size_t kMaxUnbackedValues = std::size_t{1} << 27;
constexpr std::size_t kMinUnbackedCount = std::size_t{1} << 16;

// The file's own bytes: decoded copies of its compressed bufferViews are not counted.
std::size_t bufferBytes(const tinygltf::Model& model) {
  std::size_t bytes = 0;
  for (const tinygltf::Buffer& b : model.buffers) bytes += b.name == kDecodedBufferName ? 0 : b.data.size();
  return bytes;
}

std::size_t unbackedCountLimit(const tinygltf::Model& model, std::size_t components) {
  return std::min(kMaxUnbackedValues / components, std::max(bufferBytes(model), kMinUnbackedCount));
}

std::size_t componentSize(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;  // INT and DOUBLE are not glTF 2.0 accessor types
  }
}

const char* componentName(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_INT: return "int";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "double";
    default: return "unknown component type";
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown type";
  }
}

// Byte layout of one element. Matrix columns start on 4-byte boundaries (spec 3.6.2.4), which pads
// MAT2 of bytes and MAT3 of bytes or shorts.
struct ElementLayout {
  int component_type = 0;
  bool normalized = false;
  std::size_t component_size = 0;
  std::size_t rows = 0;
  std::size_t columns = 0;
  std::size_t column_stride = 0;

  std::size_t components() const { return rows * columns; }
  std::size_t bytes() const { return columns * column_stride; }
};

ElementLayout layoutOf(int type, int component_type, bool normalized) {
  ElementLayout l;
  l.component_type = component_type;
  l.normalized = normalized;
  l.component_size = componentSize(component_type);
  switch (type) {
    case TINYGLTF_TYPE_MAT2: l.rows = l.columns = 2; break;
    case TINYGLTF_TYPE_MAT3: l.rows = l.columns = 3; break;
    case TINYGLTF_TYPE_MAT4: l.rows = l.columns = 4; break;
    default:
      l.rows = static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type)));
      l.columns = 1;
  }
  const std::size_t column_bytes = l.rows * l.component_size;
  l.column_stride = l.columns > 1 ? (column_bytes + 3) / 4 * 4 : column_bytes;
  return l;
}

template <typename T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// Spec 3.11 "Animations", normalized integers: c/255, c/65535, max(c/127, -1), max(c/32767, -1).
double decodeComponent(const unsigned char* p, const ElementLayout& l) {
  switch (l.component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double c = load<std::int8_t>(p);
      return l.normalized ? std::max(c / 127.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double c = load<std::uint8_t>(p);
      return l.normalized ? c / 255.0 : c;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double c = load<std::int16_t>(p);
      return l.normalized ? std::max(c / 32767.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double c = load<std::uint16_t>(p);
      return l.normalized ? c / 65535.0 : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<std::uint32_t>(p);
    default: return load<float>(p);
  }
}

// `count` elements from bufferView `view_index`, starting `offset` bytes into it, `stride` bytes
// apart (0: tightly packed), appended to `out`. `where` names the data in messages.
Status readBlock(const tinygltf::Model& model, long long view_index, long long offset, std::size_t count,
                 std::size_t stride, const ElementLayout& l, const std::string& where, std::vector<double>& out) {
  if (view_index < 0 || view_index >= static_cast<long long>(model.bufferViews.size())) {
    return parseError(where + ": bufferView " + std::to_string(view_index) + " does not exist");
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(view_index)];
  const std::string view_name = "bufferView " + std::to_string(view_index);
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size())) {
    return parseError(where + ": " + view_name + " names buffer " + std::to_string(view.buffer) + " which does not exist");
  }
  const std::size_t buffer_size = model.buffers[static_cast<std::size_t>(view.buffer)].data.size();
  if (view.byteLength > buffer_size || view.byteOffset > buffer_size - view.byteLength) {
    return parseError(where + ": " + view_name + " (offset " + std::to_string(view.byteOffset) + ", length " +
                      std::to_string(view.byteLength) + ") runs past the end of buffer " +
                      std::to_string(view.buffer) + " (" + std::to_string(buffer_size) + " bytes)");
  }
  if (offset < 0) return parseError(where + ": negative byteOffset " + std::to_string(offset));
  if (stride == 0) stride = l.bytes();
  if (stride < l.bytes()) {
    return parseError(where + ": " + view_name + " byteStride " + std::to_string(stride) +
                      " is smaller than one element (" + std::to_string(l.bytes()) + " bytes)");
  }
  const std::size_t start = static_cast<std::size_t>(offset);
  if (count > 0) {
    // start + (count - 1) * stride + element <= byteLength, without overflow.
    const bool fits = start <= view.byteLength && l.bytes() <= view.byteLength - start &&
                      count - 1 <= (view.byteLength - start - l.bytes()) / stride;
    if (!fits) {
      return parseError(where + ": " + std::to_string(count) + " elements of " + std::to_string(l.bytes()) +
                        " bytes from offset " + std::to_string(start) + " (stride " + std::to_string(stride) +
                        ") run past the end of " + view_name + " (" + std::to_string(view.byteLength) + " bytes)");
    }
  }
  const unsigned char* base =
      model.buffers[static_cast<std::size_t>(view.buffer)].data.data() + view.byteOffset + start;
  out.reserve(out.size() + count * l.components());
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t c = 0; c < l.columns; ++c) {
      const unsigned char* column = base + i * stride + c * l.column_stride;
      for (std::size_t r = 0; r < l.rows; ++r) {
        const double v = decodeComponent(column + r * l.component_size, l);
        if (!std::isfinite(v)) {
          return parseError(where + ": element " + std::to_string(i) + " is not a finite number");
        }
        out.push_back(v);
      }
    }
  }
  return okStatus();
}

Status applySparse(const tinygltf::Model& model, const tinygltf::Accessor& a, const ElementLayout& l,
                   const std::string& where, std::vector<double>& values) {
  const auto& sparse = a.sparse;
  if (sparse.count < 1 || static_cast<std::size_t>(sparse.count) > a.count) {
    return parseError(where + ": sparse count " + std::to_string(sparse.count) + " outside 1.." +
                      std::to_string(a.count));
  }
  const std::size_t n = static_cast<std::size_t>(sparse.count);
  const int index_type = sparse.indices.componentType;
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    return parseError(where + ": sparse indices have component type " + componentName(index_type) +
                      ", not unsigned byte, short or int");
  }
  std::vector<double> indices;
  ODESKIN_TRY(readBlock(model, sparse.indices.bufferView, sparse.indices.byteOffset, n, 0,
                        layoutOf(TINYGLTF_TYPE_SCALAR, index_type, false), where + " sparse indices", indices));
  std::vector<double> substitutes;
  ODESKIN_TRY(readBlock(model, sparse.values.bufferView, sparse.values.byteOffset, n, 0, l, where + " sparse values",
                        substitutes));
  const std::size_t width = l.components();
  for (std::size_t k = 0; k < n; ++k) {
    const double index = indices[k];
    if (index >= static_cast<double>(a.count) || (k > 0 && index <= indices[k - 1])) {
      return parseError(where + ": sparse index " + std::to_string(static_cast<std::uint64_t>(index)) + " (entry " +
                        std::to_string(k) + ") is not strictly increasing and below count " + std::to_string(a.count));
    }
    std::copy_n(substitutes.begin() + static_cast<std::ptrdiff_t>(k * width), width,
                values.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(index) * width));
  }
  return okStatus();
}

}  // namespace

DecodeBudget::DecodeBudget(const tinygltf::Model& model) {
  const std::size_t bytes = bufferBytes(model);
  limit_ = bytes > std::numeric_limits<std::size_t>::max() / kValuesPerByte
               ? std::numeric_limits<std::size_t>::max()
               : std::max(bytes * kValuesPerByte, kMinValues);
}

Status DecodeBudget::charge(std::size_t values, const std::string& what) {
  if (values > limit_ - spent_) {
    return parseError(what + ": its " + std::to_string(values) + " values would bring what the file decodes past " +
                      std::to_string(limit_) + " values (" + std::to_string(kValuesPerByte) +
                      " per byte of its buffers, at least " + std::to_string(kMinValues) +
                      "); accessors, primitives, morph targets or animation channels repeat too often");
  }
  spent_ += values;
  return okStatus();
}

Result<AccessorData> readAccessor(const tinygltf::Model& model, int index, const AccessorRequest& request,
                                  DecodeBudget& budget) {
  std::string where = "accessor " + std::to_string(index) + " (" + request.what + ")";
  if (index < 0 || index >= static_cast<int>(model.accessors.size())) {
    return parseError(where + " does not exist (" + std::to_string(model.accessors.size()) + " accessors)");
  }
  const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
  if (a.type != request.type) {
    return parseError(where + ": type " + typeName(a.type) + ", expected " + typeName(request.type));
  }
  const bool accepted = std::any_of(request.formats.begin(), request.formats.end(), [&](const AccessorFormat& f) {
    return f.component_type == a.componentType && f.normalized == a.normalized;
  });
  if (!accepted || componentSize(a.componentType) == 0) {
    std::string allowed;
    for (const AccessorFormat& f : request.formats) {
      allowed += std::string(allowed.empty() ? "" : ", ") + (f.normalized ? "normalized " : "") +
                 componentName(f.component_type);
    }
    return parseError(where + ": component type " + (a.normalized ? "normalized " : "") +
                      componentName(a.componentType) + " is not accepted here (" + allowed + ")");
  }
  if (a.count == 0) return parseError(where + ": count is 0");
  if (request.count != 0 && a.count != request.count) {
    return parseError(where + ": count " + std::to_string(a.count) + ", expected " + std::to_string(request.count));
  }
  const ElementLayout l = layoutOf(a.type, a.componentType, a.normalized);
  AccessorData data;
  data.count = a.count;
  data.components = l.components();
  if (a.bufferView >= 0) {
    if (a.byteOffset > static_cast<std::size_t>(std::numeric_limits<long long>::max())) {
      return parseError(where + ": byteOffset " + std::to_string(a.byteOffset) + " is out of range");
    }
    std::size_t stride = 0;
    if (static_cast<std::size_t>(a.bufferView) < model.bufferViews.size()) {
      stride = model.bufferViews[static_cast<std::size_t>(a.bufferView)].byteStride;
    }
    ODESKIN_TRY(readBlock(model, a.bufferView, static_cast<long long>(a.byteOffset), a.count, stride, l, where,
                          data.values));
  } else {
    const std::size_t limit = unbackedCountLimit(model, data.components);
    if (a.count > limit) {
      return parseError(where + ": count " + std::to_string(a.count) + " without a bufferView is beyond the limit of " +
                        std::to_string(limit) + " (one element per byte of the file's buffers, at least " +
                        std::to_string(kMinUnbackedCount) + ")");
    }
    data.values.assign(a.count * data.components, 0.0);
  }
  if (a.sparse.isSparse) ODESKIN_TRY(applySparse(model, a, l, where, data.values));
  // Charged once decoded: one accessor is bounded by the checks above, the sum only by the budget.
  ODESKIN_TRY(budget.charge(data.values.size(), where));
  return data;
}

}  // namespace odeskin::gltf
