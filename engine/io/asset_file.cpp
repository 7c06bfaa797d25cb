// SPDX-License-Identifier: MIT
#include "asset_file.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <map>

#include "../core/input_file.hpp"
#include "obj_io.hpp"

namespace odeskin {
namespace {

constexpr std::array<char, 8> kMagic{'O', 'D', 'S', 'K', '\r', '\n', '\x1a', '\n'};
constexpr std::size_t kHeaderBytes = 32;
constexpr std::size_t kSectionHeaderBytes = 12;  // u32 tag + u64 bytes

// Four ASCII characters read as a little-endian u32, so a hex dump shows the name.
constexpr std::uint32_t fourcc(const char (&s)[5]) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(s[0])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(s[3])) << 24;
}

// Version 1 sections, all required. Later versions may add sections; readers skip unknown tags.
constexpr std::uint32_t kMeta = fourcc("META");       // modes, residual space, skinning, segment seconds
constexpr std::uint32_t kRest = fourcc("REST");       // rest positions
constexpr std::uint32_t kFaces = fourcc("FACE");      // faces
constexpr std::uint32_t kRender = fourcc("RNDR");     // render layout
constexpr std::uint32_t kBindings = fourcc("BIND");   // curve bindings
constexpr std::uint32_t kCurves = fourcc("CURV");     // iso-curves with points and v
constexpr std::uint32_t kCurveMaterials = fourcc("CMAT");
constexpr std::uint32_t kMaterials = fourcc("MATL");
constexpr std::uint32_t kInfluences = fourcc("INFL");
constexpr std::uint32_t kBones = fourcc("BONE");      // count, pivots, parents, names
constexpr std::uint32_t kKeyPoses = fourcc("KEYS");
constexpr std::uint32_t kSegments = fourcc("SEGM");
constexpr std::array<std::uint32_t, 12> kRequired{kMeta,  kRest,           kFaces,     kRender,
                                                   kBindings, kCurves,     kCurveMaterials, kMaterials,
                                                   kInfluences, kBones,    kKeyPoses,  kSegments};
// Optional sections, written only when the asset has their data; a version 1 reader that predates
// one skips it as a later version's (the asset then plays as before, without what it adds).
constexpr std::uint32_t kRenderNormals = fourcc("RNRM");  // the render layout's bind normals (hard edges)
constexpr std::uint32_t kRenderUvs = fourcc("RUV0");      // the render layout's TEXCOORD_0
constexpr std::uint32_t kRenderPrimitives = fourcc("RPRM");  // the render layout's primitives and materials
// Empty: present when the render layout came from an OBJ (RenderLayout::obj_order). A reader that
// predates it writes OBJ frames in render order, as it did for every layout.
constexpr std::uint32_t kRenderObjOrder = fourcc("ROBJ");
constexpr std::array<std::uint32_t, 4> kOptional{kRenderNormals, kRenderUvs, kRenderPrimitives, kRenderObjOrder};

std::string tagName(std::uint32_t tag) {
  std::string name;
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((tag >> (8 * i)) & 0xFFu);
    name += (c >= 0x20 && c < 0x7F) ? c : '?';
  }
  return "'" + name + "'";
}

// ---- writing -----------------------------------------------------------------------------------

class Writer {
 public:
  void u8(std::uint8_t x) { bytes_.push_back(static_cast<char>(x)); }
  void u32(std::uint32_t x) { put(x, 4); }
  void i32(std::int32_t x) { u32(static_cast<std::uint32_t>(x)); }
  void u64(std::uint64_t x) { put(x, 8); }
  void f64(double x) { u64(std::bit_cast<std::uint64_t>(x)); }
  void vec3(const Vec3& v) { f64(v.x); f64(v.y); f64(v.z); }
  void count(std::size_t n) { u64(static_cast<std::uint64_t>(n)); }
  void text(const std::string& s) {
    count(s.size());
    bytes_ += s;
  }
  void u32s(const std::vector<std::uint32_t>& xs) {
    count(xs.size());
    for (std::uint32_t x : xs) u32(x);
  }
  void i32s(const std::vector<std::int32_t>& xs) {
    count(xs.size());
    for (std::int32_t x : xs) i32(x);
  }
  void f64s(const std::vector<double>& xs) {
    count(xs.size());
    for (double x : xs) f64(x);
  }
  void vec3s(const std::vector<Vec3>& xs) {
    count(xs.size());
    for (const Vec3& x : xs) vec3(x);
  }
  void vec2s(const std::vector<Vec2>& xs) {
    count(xs.size());
    for (const Vec2& x : xs) {
      f64(x.x);
      f64(x.y);
    }
  }
  void faces(const FaceList& f) {
    u32s(f.face_offsets);
    u32s(f.indices);
  }

  // Opens a section; endSection patches its byte count.
  void beginSection(std::uint32_t tag) {
    u32(tag);
    section_start_ = bytes_.size();
    u64(0);
  }
  void endSection() {
    const std::uint64_t size = bytes_.size() - section_start_ - 8;
    for (int i = 0; i < 8; ++i) bytes_[section_start_ + i] = static_cast<char>((size >> (8 * i)) & 0xFFu);
  }

  std::string& bytes() { return bytes_; }

 private:
  void put(std::uint64_t x, int n) {
    for (int i = 0; i < n; ++i) bytes_.push_back(static_cast<char>((x >> (8 * i)) & 0xFFu));
  }

  std::string bytes_;
  std::size_t section_start_ = 0;
};

void writeSections(const DeformAsset& a, Writer& w) {
  w.beginSection(kMeta);
  w.i32(a.modes);
  w.u32(a.residual_space == ResidualSpace::kPosed ? 1u : 0u);
  w.u32(static_cast<std::uint32_t>(a.skinning));
  w.f64(a.segment_seconds);
  w.endSection();

  w.beginSection(kRest);
  w.vec3s(a.rest_positions);
  w.endSection();

  w.beginSection(kFaces);
  w.faces(a.faces);
  w.endSection();

  w.beginSection(kRender);
  w.u32s(a.render.topology_of_render);
  w.faces(a.render.faces);
  w.endSection();

  if (!a.render.normals.empty()) {
    w.beginSection(kRenderNormals);
    w.vec3s(a.render.normals);
    w.endSection();
  }
  if (!a.render.uvs.empty()) {
    w.beginSection(kRenderUvs);
    w.vec2s(a.render.uvs);
    w.endSection();
  }
  if (a.render.obj_order) {
    w.beginSection(kRenderObjOrder);
    w.endSection();
  }
  if (!a.render.primitives.empty()) {
    w.beginSection(kRenderPrimitives);
    w.count(a.render.primitives.size());
    for (const RenderPrimitive& p : a.render.primitives) {
      w.u32(p.face_end);
      w.i32(p.material);
    }
    w.endSection();
  }

  w.beginSection(kBindings);
  w.count(a.bindings.size());
  for (const CurveBinding& b : a.bindings) {
    w.u32(b.curve_a);
    w.u32(b.curve_b);
    w.f64(b.w);
    w.f64(b.v);
  }
  w.endSection();

  w.beginSection(kCurves);
  w.count(a.curves.size());
  for (const IsoCurve& c : a.curves) {
    w.u32(c.part);
    w.u8(c.closed ? 1 : 0);
    w.count(c.points.size());
    for (const CurvePoint& p : c.points) {
      w.u32(p.a);
      w.u32(p.b);
      w.f64(p.t);
    }
    w.f64s(c.v);
  }
  w.endSection();

  w.beginSection(kCurveMaterials);
  w.u32s(a.curve_materials);
  w.endSection();

  w.beginSection(kMaterials);
  w.count(a.materials.size());
  for (const Material& m : a.materials) {
    w.f64(m.rho);
    w.f64(m.eta);
    w.f64(m.zeta);
    w.f64(m.xi);
    w.u32(m.bending == BendingSign::kStiffening ? 1u : 0u);
  }
  w.endSection();

  w.beginSection(kInfluences);
  w.u32s(a.influences.offsets);
  w.u32s(a.influences.bones);
  w.f64s(a.influences.weights);
  w.endSection();

  w.beginSection(kBones);
  w.u32(a.bone_count);
  w.vec3s(a.bone_pivots);
  w.i32s(a.bone_parents);
  w.count(a.bone_names.size());
  for (const std::string& name : a.bone_names) w.text(name);
  w.endSection();

  w.beginSection(kKeyPoses);
  w.count(a.key_poses.size());
  for (const std::vector<RigidTransform>& pose : a.key_poses) {
    w.count(pose.size());
    for (const RigidTransform& t : pose) {
      w.f64(t.rotation.w);
      w.f64(t.rotation.x);
      w.f64(t.rotation.y);
      w.f64(t.rotation.z);
      w.vec3(t.translation);
    }
  }
  w.endSection();

  w.beginSection(kSegments);
  w.count(a.segments.size());
  for (const DeformSegment& s : a.segments) {
    w.vec3s(s.base_residuals);
    w.vec3s(s.coefficients);
    w.vec3s(s.rates);
    w.u32s(s.remainder_indices);
    w.vec3s(s.remainders);
  }
  w.endSection();
}

// ---- reading -----------------------------------------------------------------------------------

// Bounds-checked little-endian reads over one section. The first failure sticks: later reads
// return zeros, and the section parser checks ok() once at the end.
class Reader {
 public:
  Reader(std::string_view data, std::string section) : data_(data), section_(std::move(section)) {}

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  std::size_t remaining() const { return data_.size() - pos_; }

  std::uint8_t u8() { return static_cast<std::uint8_t>(get(1)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(get(4)); }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  std::uint64_t u64() { return get(8); }
  double f64() { return std::bit_cast<double>(get(8)); }
  Vec3 vec3() {
    const double x = f64();
    const double y = f64();
    const double z = f64();
    return Vec3(x, y, z);
  }

  // An element count, rejected when that many elements of at least `min_element_bytes` cannot
  // fit in the rest of the section (so a corrupt count never allocates gigabytes).
  std::size_t count(std::size_t min_element_bytes) {
    const std::uint64_t n = u64();
    if (!ok()) return 0;
    if (min_element_bytes > 0 && n > remaining() / min_element_bytes) {
      fail("count " + std::to_string(n) + " overruns the section");
      return 0;
    }
    return static_cast<std::size_t>(n);
  }
  std::string text() {
    const std::size_t n = count(1);
    if (!ok()) return {};
    std::string s(data_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  std::vector<std::uint32_t> u32s() { return array<std::uint32_t>(4, [this] { return u32(); }); }
  std::vector<std::int32_t> i32s() { return array<std::int32_t>(4, [this] { return i32(); }); }
  std::vector<double> f64s() { return array<double>(8, [this] { return f64(); }); }
  std::vector<Vec3> vec3s() { return array<Vec3>(24, [this] { return vec3(); }); }
  std::vector<Vec2> vec2s() {
    return array<Vec2>(16, [this] {
      const double u = f64();
      const double v = f64();
      return Vec2(u, v);
    });
  }
  FaceList faces() {
    FaceList f;
    f.face_offsets = u32s();
    f.indices = u32s();
    return f;
  }

  void fail(const std::string& what) {
    if (ok()) error_ = "section " + section_ + ": " + what;
  }

 private:
  std::uint64_t get(int n) {
    if (!ok()) return 0;
    if (remaining() < static_cast<std::size_t>(n)) {
      fail("ends early at byte " + std::to_string(pos_));
      return 0;
    }
    std::uint64_t x = 0;
    for (int i = 0; i < n; ++i) x |= static_cast<std::uint64_t>(static_cast<unsigned char>(data_[pos_ + i])) << (8 * i);
    pos_ += static_cast<std::size_t>(n);
    return x;
  }

  template <typename T, typename ReadOne>
  std::vector<T> array(std::size_t element_bytes, ReadOne read_one) {
    const std::size_t n = count(element_bytes);
    std::vector<T> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n && ok(); ++i) out.push_back(read_one());
    return out;
  }

  std::string_view data_;
  std::size_t pos_ = 0;
  std::string section_;
  std::string error_;
};

void readSection(std::uint32_t tag, Reader& r, DeformAsset& a) {
  if (tag == kMeta) {
    a.modes = r.i32();
    const std::uint32_t space = r.u32();
    if (space > 1) r.fail("unknown residual space " + std::to_string(space));
    a.residual_space = space == 1 ? ResidualSpace::kPosed : ResidualSpace::kBind;
    const std::uint32_t skinning = r.u32();
    if (skinning > 1) r.fail("unknown skinning mode " + std::to_string(skinning));
    a.skinning = static_cast<SkinningMode>(skinning);
    a.segment_seconds = r.f64();
  } else if (tag == kRest) {
    a.rest_positions = r.vec3s();
  } else if (tag == kFaces) {
    a.faces = r.faces();
  } else if (tag == kRender) {
    a.render.topology_of_render = r.u32s();
    a.render.faces = r.faces();
  } else if (tag == kRenderNormals) {
    a.render.normals = r.vec3s();
  } else if (tag == kRenderUvs) {
    a.render.uvs = r.vec2s();
  } else if (tag == kRenderObjOrder) {
    a.render.obj_order = true;
  } else if (tag == kRenderPrimitives) {
    a.render.primitives.resize(r.count(8));
    for (RenderPrimitive& p : a.render.primitives) {
      p.face_end = r.u32();
      p.material = r.i32();
    }
  } else if (tag == kBindings) {
    a.bindings.resize(r.count(24));
    for (CurveBinding& b : a.bindings) {
      b.curve_a = r.u32();
      b.curve_b = r.u32();
      b.w = r.f64();
      b.v = r.f64();
    }
  } else if (tag == kCurves) {
    a.curves.resize(r.count(21));
    for (IsoCurve& c : a.curves) {
      c.part = r.u32();
      const std::uint8_t closed = r.u8();
      if (closed > 1) r.fail("curve closed flag " + std::to_string(closed) + " is not 0 or 1");
      c.closed = closed == 1;
      c.points.resize(r.count(16));
      for (CurvePoint& p : c.points) {
        p.a = r.u32();
        p.b = r.u32();
        p.t = r.f64();
      }
      c.v = r.f64s();
    }
  } else if (tag == kCurveMaterials) {
    a.curve_materials = r.u32s();
  } else if (tag == kMaterials) {
    a.materials.resize(r.count(36));
    for (Material& m : a.materials) {
      m.rho = r.f64();
      m.eta = r.f64();
      m.zeta = r.f64();
      m.xi = r.f64();
      const std::uint32_t bending = r.u32();
      if (bending > 1) r.fail("unknown bending sign " + std::to_string(bending));
      m.bending = bending == 1 ? BendingSign::kStiffening : BendingSign::kThesis;
    }
  } else if (tag == kInfluences) {
    a.influences.offsets = r.u32s();
    a.influences.bones = r.u32s();
    a.influences.weights = r.f64s();
  } else if (tag == kBones) {
    a.bone_count = r.u32();
    a.bone_pivots = r.vec3s();
    a.bone_parents = r.i32s();
    a.bone_names.resize(r.count(8));
    for (std::string& name : a.bone_names) name = r.text();
  } else if (tag == kKeyPoses) {
    a.key_poses.resize(r.count(8));
    for (std::vector<RigidTransform>& pose : a.key_poses) {
      pose.resize(r.count(56));
      for (RigidTransform& t : pose) {
        t.rotation.w = r.f64();
        t.rotation.x = r.f64();
        t.rotation.y = r.f64();
        t.rotation.z = r.f64();
        t.translation = r.vec3();
      }
    }
  } else if (tag == kSegments) {
    a.segments.resize(r.count(40));
    for (DeformSegment& s : a.segments) {
      s.base_residuals = r.vec3s();
      s.coefficients = r.vec3s();
      s.rates = r.vec3s();
      s.remainder_indices = r.u32s();
      s.remainders = r.vec3s();
    }
  }
}

std::uint64_t readLe(const std::string& bytes, std::size_t offset, int n) {
  std::uint64_t x = 0;
  for (int i = 0; i < n; ++i) {
    x |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[offset + static_cast<std::size_t>(i)])) << (8 * i);
  }
  return x;
}

// Checks magic, version, flags, size and checksum; returns the payload.
Result<std::string_view> checkHeader(const std::string& bytes, const std::string& source) {
  if (bytes.size() < kHeaderBytes) {
    if (bytes.size() >= kMagic.size() && !std::equal(kMagic.begin(), kMagic.end(), bytes.begin())) {
      return parseError(source + ": not an odeskin asset (bad magic)");
    }
    return parseError(source + ": truncated: " + std::to_string(bytes.size()) + " bytes, the header alone has " +
                      std::to_string(kHeaderBytes));
  }
  if (!std::equal(kMagic.begin(), kMagic.end(), bytes.begin())) {
    return parseError(source + ": not an odeskin asset (bad magic)");
  }
  const std::uint64_t version = readLe(bytes, 8, 4);
  if (version == 0 || version > kAssetVersion) {
    return parseError(source + ": asset format version " + std::to_string(version) + " is not supported (this build reads 1 to " +
                      std::to_string(kAssetVersion) + ")");
  }
  const std::uint64_t flags = readLe(bytes, 12, 4);
  if (flags != 0) return parseError(source + ": unknown header flags " + std::to_string(flags));
  const std::uint64_t payload_bytes = readLe(bytes, 16, 8);
  if (payload_bytes != bytes.size() - kHeaderBytes) {
    return parseError(source + ": truncated or padded: the header announces " + std::to_string(payload_bytes) +
                      " payload bytes, the file has " + std::to_string(bytes.size() - kHeaderBytes));
  }
  const std::string_view payload = std::string_view(bytes).substr(kHeaderBytes);
  const std::uint64_t stored = readLe(bytes, 24, 8);
  if (assetChecksum(payload) != stored) {
    return parseError(source + ": checksum mismatch: the file is corrupted");
  }
  return payload;
}

}  // namespace

std::uint64_t assetChecksum(std::string_view payload) {
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a 64 offset basis
  for (char c : payload) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;  // FNV-1a 64 prime
  }
  return hash;
}

Result<std::string> encodeAsset(const DeformAsset& asset) {
  ODESKIN_TRY(validateDeformAsset(asset));
  Writer payload;
  writeSections(asset, payload);
  Writer file;
  for (char c : kMagic) file.u8(static_cast<std::uint8_t>(c));
  file.u32(kAssetVersion);
  file.u32(0);
  file.count(payload.bytes().size());
  file.u64(assetChecksum(payload.bytes()));
  file.bytes() += payload.bytes();
  return std::move(file.bytes());
}

Result<DeformAsset> decodeAsset(const std::string& bytes, const std::string& source) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string_view payload, checkHeader(bytes, source));
  DeformAsset asset;
  std::map<std::uint32_t, bool> seen;
  std::size_t pos = 0;
  while (pos < payload.size()) {
    if (payload.size() - pos < kSectionHeaderBytes) {
      return parseError(source + ": a section header at payload byte " + std::to_string(pos) + " is cut short");
    }
    const std::uint32_t tag = static_cast<std::uint32_t>(readLe(bytes, kHeaderBytes + pos, 4));
    const std::uint64_t size = readLe(bytes, kHeaderBytes + pos + 4, 8);
    pos += kSectionHeaderBytes;
    if (size > payload.size() - pos) {
      return parseError(source + ": section " + tagName(tag) + " (" + std::to_string(size) +
                        " bytes) overruns the payload at byte " + std::to_string(pos));
    }
    const std::string_view data = payload.substr(pos, static_cast<std::size_t>(size));
    pos += static_cast<std::size_t>(size);
    if (std::find(kRequired.begin(), kRequired.end(), tag) == kRequired.end() &&
        std::find(kOptional.begin(), kOptional.end(), tag) == kOptional.end()) {
      continue;  // a later version's
    }
    if (seen[tag]) return parseError(source + ": section " + tagName(tag) + " appears twice");
    seen[tag] = true;
    Reader reader(data, tagName(tag));
    readSection(tag, reader, asset);
    if (reader.ok() && reader.remaining() != 0) {
      reader.fail(std::to_string(reader.remaining()) + " bytes left unread");
    }
    if (!reader.ok()) return parseError(source + ": " + reader.error());
  }
  for (std::uint32_t tag : kRequired) {
    if (!seen[tag]) return parseError(source + ": missing required section " + tagName(tag));
  }
  Status valid = validateDeformAsset(asset);
  if (!valid.ok()) return Status(valid.code(), source + ": " + valid.message());
  return asset;
}

Status saveAsset(const std::filesystem::path& path, const DeformAsset& asset) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string bytes, encodeAsset(asset));
  return writeFileAtomically(path, bytes);
}

Result<DeformAsset> loadAsset(const std::filesystem::path& path) {
  ODESKIN_ASSIGN_OR_RETURN(const std::string bytes, readInputFile(path));
  return decodeAsset(bytes, path.string());
}

}  // namespace odeskin
