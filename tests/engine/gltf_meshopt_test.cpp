// SPDX-License-Identifier: MIT
// EXT_meshopt_compression input (engine/io/gltf_meshopt.hpp): small files compressed here with
// meshoptimizer's encoders, in GLB and .gltf framing, with the placeholder buffer gltfpack writes;
// every mode and filter decodes to what the codec gives back, and every rule of the extension and
// every broken input is refused naming the bufferView. tests/interop reads gltfpack's own output.
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "engine/io/gltf_accessor.hpp"
#include "engine/io/gltf_load.hpp"

namespace odeskin::gltf {
namespace {

using Bytes = std::vector<unsigned char>;

void put32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

// A GLB of `json` and `bin` (the BIN chunk, buffer 0), both padded as the container requires.
std::string glb(const nlohmann::json& json, Bytes bin) {
  std::string text = json.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  bin.resize((bin.size() + 3) / 4 * 4, 0);
  std::string out = "glTF";
  put32(out, 2);
  put32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  put32(out, static_cast<std::uint32_t>(text.size()));
  put32(out, 0x4E4F534A);  // JSON
  out += text;
  put32(out, static_cast<std::uint32_t>(bin.size()));
  put32(out, 0x004E4942);  // BIN
  out.append(bin.begin(), bin.end());
  return out;
}

template <typename T>
Bytes bytesOf(const std::vector<T>& values) {
  Bytes out(values.size() * sizeof(T));
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

Bytes encodeAttributes(const Bytes& raw, std::size_t stride) {
  const std::size_t count = raw.size() / stride;
  Bytes out(meshopt_encodeVertexBufferBound(count, stride));
  out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), raw.data(), count, stride));
  return out;
}

// One compressed bufferView of `raw` (count x stride bytes): the compressed bytes in buffer 0 (the
// BIN chunk), the bufferView itself in buffer 1, a placeholder without a uri, tagged as fallback.
// NOLINTNEXTLINE(bugprone-exception-escape): nlohmann::json's moves may throw; a test may abort on it
struct OneView {
  nlohmann::json json;
  Bytes bin;
};

OneView oneView(const Bytes& compressed, std::size_t raw_bytes, std::size_t stride, const std::string& mode,
                const std::string& filter = "NONE") {
  OneView v;
  v.bin = compressed;
  nlohmann::json ext = {{"buffer", 0},          {"byteOffset", 0},
                        {"byteLength", compressed.size()}, {"byteStride", stride},
                        {"count", raw_bytes / stride},      {"mode", mode}};
  if (filter != "NONE") ext["filter"] = filter;
  v.json = {{"asset", {{"version", "2.0"}}},
            {"extensionsUsed", {"EXT_meshopt_compression"}},
            {"extensionsRequired", {"EXT_meshopt_compression"}},
            {"buffers",
             {{{"byteLength", compressed.size()}},
              {{"byteLength", raw_bytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
            {"bufferViews", {{{"buffer", 1}, {"byteLength", raw_bytes}, {"extensions", {{"EXT_meshopt_compression", ext}}}}}}};
  return v;
}

Result<tinygltf::Model> load(const OneView& v) { return loadModelFromMemory(glb(v.json, v.bin), "test.glb"); }

Bytes viewBytes(const tinygltf::Model& m, int view) {
  const tinygltf::BufferView& bv = m.bufferViews[static_cast<std::size_t>(view)];
  const auto& data = m.buffers[static_cast<std::size_t>(bv.buffer)].data;
  return Bytes(data.begin() + static_cast<std::ptrdiff_t>(bv.byteOffset),
               data.begin() + static_cast<std::ptrdiff_t>(bv.byteOffset + bv.byteLength));
}

// Positions of a small strip: 40 float3 (stride 12).
Bytes positions() {
  std::vector<float> p;
  for (int i = 0; i < 40; ++i) {
    p.push_back(0.1f * static_cast<float>(i));
    p.push_back(static_cast<float>(i % 2));
    p.push_back(-0.25f * static_cast<float>(i % 5));
  }
  return bytesOf(p);
}

TEST(GltfMeshopt, AttributesDecodeExactlyFromAGlbWithAPlaceholderBuffer) {
  const Bytes raw = positions();
  Result<tinygltf::Model> m = load(oneView(encodeAttributes(raw, 12), raw.size(), 12, "ATTRIBUTES"));
  ASSERT_TRUE(m.ok()) << m.status().toString();
  EXPECT_EQ(viewBytes(*m, 0), raw);
  EXPECT_EQ(m->bufferViews[0].byteOffset, 0u);
  EXPECT_TRUE(checkRequiredExtensions(*m).ok());
}

TEST(GltfMeshopt, AJsonFileWithADataUriAndAPlaceholderWithoutUri) {
  const Bytes raw = positions();
  OneView v = oneView(encodeAttributes(raw, 12), raw.size(), 12, "ATTRIBUTES");
  std::string base64;
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (std::size_t i = 0; i < v.bin.size(); i += 3) {
    const std::uint32_t n = (std::uint32_t{v.bin[i]} << 16) | (i + 1 < v.bin.size() ? std::uint32_t{v.bin[i + 1]} << 8 : 0u) |
                            (i + 2 < v.bin.size() ? std::uint32_t{v.bin[i + 2]} : 0u);
    base64 += kDigits[(n >> 18) & 63];
    base64 += kDigits[(n >> 12) & 63];
    base64 += i + 1 < v.bin.size() ? kDigits[(n >> 6) & 63] : '=';
    base64 += i + 2 < v.bin.size() ? kDigits[n & 63] : '=';
  }
  v.json["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64;
  v.json["buffers"][1].erase("extensions");  // a placeholder by having no uri alone
  Result<tinygltf::Model> m = loadModelFromMemory(v.json.dump(), "test.gltf");
  ASSERT_TRUE(m.ok()) << m.status().toString();
  EXPECT_EQ(viewBytes(*m, 0), raw);
}

TEST(GltfMeshopt, TrianglesAndIndicesDecode) {
  const std::vector<std::uint32_t> triangles = {0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5, 4, 5, 6, 6, 5, 7};
  for (const std::size_t stride : {std::size_t{2}, std::size_t{4}}) {
    Bytes raw(triangles.size() * stride);
    for (std::size_t k = 0; k < triangles.size(); ++k) std::memcpy(&raw[k * stride], &triangles[k], stride);
    Bytes tri(meshopt_encodeIndexBufferBound(triangles.size(), 8));
    tri.resize(meshopt_encodeIndexBuffer(tri.data(), tri.size(), triangles.data(), triangles.size()));
    Result<tinygltf::Model> t = load(oneView(tri, raw.size(), stride, "TRIANGLES"));
    ASSERT_TRUE(t.ok()) << t.status().toString();
    // The codec may start a triangle at another corner (its winding kept); the expectation is what
    // meshoptimizer's own decoder gives.
    Bytes expected(raw.size());
    ASSERT_EQ(meshopt_decodeIndexBuffer(expected.data(), triangles.size(), stride, tri.data(), tri.size()), 0);
    EXPECT_EQ(viewBytes(*t, 0), expected) << "stride " << stride;

    Bytes seq(meshopt_encodeIndexSequenceBound(triangles.size(), 8));
    seq.resize(meshopt_encodeIndexSequence(seq.data(), seq.size(), triangles.data(), triangles.size()));
    Result<tinygltf::Model> s = load(oneView(seq, raw.size(), stride, "INDICES"));
    ASSERT_TRUE(s.ok()) << s.status().toString();
    EXPECT_EQ(viewBytes(*s, 0), raw) << "stride " << stride;
  }
}

// Each filter: the encoded values compressed, decoded and filtered as meshoptimizer does it.
TEST(GltfMeshopt, FiltersDecodeAsTheCodecDoes) {
  struct Case {
    const char* filter;
    std::size_t stride;
    void (*encode)(void*, std::size_t, std::size_t, int, const float*);
    void (*decode)(void*, std::size_t, std::size_t);
    int bits;
  };
  const Case cases[] = {{"OCTAHEDRAL", 4, meshopt_encodeFilterOct, meshopt_decodeFilterOct, 8},
                        {"OCTAHEDRAL", 8, meshopt_encodeFilterOct, meshopt_decodeFilterOct, 12},
                        {"QUATERNION", 8, meshopt_encodeFilterQuat, meshopt_decodeFilterQuat, 12},
                        {"EXPONENTIAL", 12, meshopt_encodeFilterExp, meshopt_decodeFilterExp, 15}};
  constexpr std::size_t kCount = 24;
  for (const Case& c : cases) {
    // Unit vectors (w = 1) or unit quaternions; any floats for the exponential filter.
    std::vector<float> data;
    for (std::size_t i = 0; i < kCount; ++i) {
      const float a = 0.3f * static_cast<float>(i), b = 0.17f * static_cast<float>(i);
      if (c.stride == 12) {
        data.insert(data.end(), {std::sin(a) * 40.0f, std::cos(b), 1e-3f * static_cast<float>(i)});
      } else {
        const float x = std::cos(a) * std::cos(b), y = std::sin(a) * std::cos(b), z = std::sin(b);
        data.insert(data.end(), {x * 0.6f, y * 0.6f, z * 0.6f, c.filter[0] == 'Q' ? 0.8f : 1.0f});
      }
    }
    Bytes encoded(kCount * c.stride);
    c.encode(encoded.data(), kCount, c.stride, c.bits, data.data());
    Bytes expected = encoded;
    c.decode(expected.data(), kCount, c.stride);
    Result<tinygltf::Model> m = load(oneView(encodeAttributes(encoded, c.stride), encoded.size(), c.stride, "ATTRIBUTES", c.filter));
    ASSERT_TRUE(m.ok()) << c.filter << ": " << m.status().toString();
    EXPECT_EQ(viewBytes(*m, 0), expected) << c.filter << " stride " << c.stride;
  }
}

// 4 MiB of zeros compress to 64 KiB; the read's decode budget stays that of a 64 KiB file
// (DecodeBudget's floor), not the 2^27 values 4 MiB of buffers would allow.
TEST(GltfMeshopt, DecodedBytesDoNotRaiseTheDecodeBudget) {
  const Bytes zeros(std::size_t{4} << 20, 0);
  const Bytes packed = encodeAttributes(zeros, 16);
  ASSERT_LT(packed.size() * DecodeBudget::kValuesPerByte, DecodeBudget::kMinValues);
  Result<tinygltf::Model> m = load(oneView(packed, zeros.size(), 16, "ATTRIBUTES"));
  ASSERT_TRUE(m.ok()) << m.status().toString();
  EXPECT_EQ(viewBytes(*m, 0), zeros);
  DecodeBudget budget(*m);
  EXPECT_TRUE(budget.charge(DecodeBudget::kMinValues, "the floor").ok());
  EXPECT_FALSE(budget.charge(1, "one more value").ok());
}

void expectRefused(const OneView& v, const std::string& words, StatusCode code = StatusCode::kParseError) {
  Result<tinygltf::Model> m = load(v);
  ASSERT_FALSE(m.ok()) << "accepted; expected '" << words << "'";
  EXPECT_EQ(m.status().code(), code) << m.status().toString();
  EXPECT_NE(m.status().message().find(words), std::string::npos) << m.status().message();
  EXPECT_NE(m.status().message().find("test.glb"), std::string::npos) << m.status().message();
}

TEST(GltfMeshopt, TheExtensionsRulesAndBrokenDataAreRefusedNamingTheBufferView) {
  const Bytes raw = positions();
  const Bytes packed = encodeAttributes(raw, 12);
  const OneView good = oneView(packed, raw.size(), 12, "ATTRIBUTES");
  auto with = [&](const char* key, const nlohmann::json& value) {
    OneView v = good;
    v.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"][key] = value;
    return v;
  };
  {
    OneView v = good;
    v.json["bufferViews"][0]["byteStride"] = 16;
    expectRefused(v, "bufferView 0's EXT_meshopt_compression has byteStride 12 but the bufferView 16");
  }
  expectRefused(with("count", 39), "holds 39 elements of 12 bytes, not the bufferView's byteLength 480");
  {
    OneView v = with("byteStride", 6);
    v.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 80;
    expectRefused(v, "mode ATTRIBUTES needs a byteStride divisible by 4 and at most 256, not 6");
  }
  {
    OneView v = with("mode", "TRIANGLES");
    v.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 4;
    v.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 120;
    v.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["filter"] = "OCTAHEDRAL";
    expectRefused(v, "mode TRIANGLES takes no filter, not OCTAHEDRAL");
  }
  {
    OneView v = with("mode", "TRIANGLES");
    v.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 4;
    v.json["bufferViews"][0]["byteLength"] = 4 * 121;
    v.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 121;
    expectRefused(v, "mode TRIANGLES needs a count divisible by 3, not 121");
  }
  expectRefused(with("mode", "INDICES"), "mode INDICES needs a byteStride of 2 or 4, not 12");
  expectRefused(with("mode", "STRIPS"), "has the unknown mode \"STRIPS\"");
  expectRefused(with("filter", "OCTAHEDRAL"), "filter OCTAHEDRAL does not allow byteStride 12");
  expectRefused(with("filter", "ZIGZAG"), "has the unknown filter \"ZIGZAG\"");
  expectRefused(with("buffer", 7), "names buffer 7 of 2");
  expectRefused(with("byteLength", packed.size() + 100), "lie outside buffer 0");
  expectRefused(with("byteLength", -1), "has no whole, non-negative \"byteLength\"");
  {
    // The placeholder may not be the source of compressed data (it now holds one byte).
    OneView v = with("buffer", 1);
    expectRefused(v, "lie outside buffer 1");
  }
  // A stream cut short, and one that is not an attribute stream at all.
  expectRefused(with("byteLength", packed.size() - 40), "does not decode: meshoptimizer 0.18 returned");
  {
    OneView v = good;
    v.bin[0] = 0xa1;  // the version 1 header meshoptimizer 0.18 does not know
    expectRefused(v, "does not decode: meshoptimizer 0.18 returned");
  }
  {
    // 64 MiB from a few hundred bytes.
    OneView v = with("count", 1u << 22);
    v.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 16;
    v.json["bufferViews"][0]["byteLength"] = std::uint64_t{16} << 22;
    expectRefused(v, "would decode 67108864 bytes, past the");
  }
  {
    OneView v = good;
    v.json["bufferViews"][0]["extensions"]["KHR_meshopt_compression"] = v.json["bufferViews"][0]["extensions"]["EXT_meshopt_compression"];
    v.json["bufferViews"][0]["extensions"].erase("EXT_meshopt_compression");
    expectRefused(v, "compressed with KHR_meshopt_compression", StatusCode::kInvalidArgument);
  }
}

}  // namespace
}  // namespace odeskin::gltf
