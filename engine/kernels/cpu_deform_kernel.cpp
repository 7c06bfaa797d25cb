// SPDX-License-Identifier: MIT
#include "cpu_deform_kernel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/task_arena.h>

#include "simd_deform_layout.hpp"
#include "../core/parallel.hpp"
#include "../core/thread_count.hpp"

namespace odeskin {

using simd_deform::Block;
using simd_deform::kBlockLanes;
using simd_deform::Layout;

namespace {

constexpr const char* kWho = "cpu deform kernel: ";
// 256 blocks (4096 vertices) per task, as fourier_deform_fast_job's grain: a task is ~100 us of
// work at N = 9, so scheduling is noise, and a 1e4-vertex mesh still splits over a few threads.
constexpr std::size_t kGrainBlocks = 256;

Status invalid(const std::string& what) { return invalidArgument(kWho + what); }

std::string str(std::size_t n) { return std::to_string(n); }

// The vertex's influence entries (sparse row or fixed slots).
std::span<const gpu::Influence> influenceRow(const PackedDeformData& d, std::size_t i) {
  if (d.influence_layout == ODESKIN_INFLUENCES_SPARSE) {
    return std::span(d.influences).subspan(d.influence_offsets[i], d.influence_offsets[i + 1] - d.influence_offsets[i]);
  }
  return std::span(d.influences).subspan(i * d.influence_layout, d.influence_layout);
}

Status checkSizes(const PackedDeformData& d) {
  const std::uint32_t layout = d.influence_layout;
  if (layout != ODESKIN_INFLUENCES_SPARSE && layout != 4 && layout != 8) {
    return invalid("influence_layout " + str(layout) + " is not 0, 4 or 8");
  }
  if (d.skinning != SkinningMode::kLinear && d.skinning != SkinningMode::kDualQuaternion) {
    return invalid("unknown skinning mode " + str(static_cast<std::uint32_t>(d.skinning)));
  }
  if (d.residual_space != ResidualSpace::kBind && d.residual_space != ResidualSpace::kPosed) {
    return invalid("unknown residual space " + str(static_cast<std::uint32_t>(d.residual_space)));
  }
  if (d.modes > simd_deform::kMaxModes) {
    return outOfRange(kWho + std::string("N = ") + str(d.modes) + " modes, at most " + str(simd_deform::kMaxModes));
  }
  const std::size_t v = d.vertex_count;
  const std::size_t m_count = d.coefficientsPerCurve();
  if (d.rest_positions.size() != v) return invalid("rest_positions has " + str(d.rest_positions.size()) + ", expected " + str(v));
  if (d.bindings.size() != v) return invalid("bindings has " + str(d.bindings.size()) + ", expected " + str(v));
  if (d.segment_vertices.size() != d.segment_count * v) {
    return invalid("segment_vertices has " + str(d.segment_vertices.size()) + ", expected segment_count x vertex_count");
  }
  if (d.curve_materials.size() != d.curve_count) return invalid("curve_materials size differs from curve_count");
  if (d.coefficients.size() != std::size_t{d.segment_count} * d.curve_count * m_count) {
    return invalid("coefficients has " + str(d.coefficients.size()) + ", expected segment_count x curve_count x (2N+2)");
  }
  if (!d.rates.empty() && d.rates.size() != d.coefficients.size()) return invalid("rates size differs from coefficients");
  if (d.remainder_base.size() != d.segment_count) return invalid("remainder_base size differs from segment_count");
  if (layout == ODESKIN_INFLUENCES_SPARSE) {
    if (d.influence_offsets.size() != v + 1 || d.influence_offsets.front() != 0 ||
        d.influences.size() != d.influence_offsets.back()) {
      return invalid("sparse influence rows do not match vertex_count");
    }
    for (std::size_t i = 0; i < v; ++i) {
      if (d.influence_offsets[i] > d.influence_offsets[i + 1]) return invalid("influence_offsets decrease at vertex " + str(i));
    }
  } else if (d.influences.size() != v * layout) {
    return invalid("influences size is not vertex_count x slots");
  }
  return okStatus();
}

Status checkIndices(const PackedDeformData& d) {
  for (std::size_t c = 0; c < d.curve_count; ++c) {
    if (d.curve_materials[c] >= d.material_count) {
      return invalid("curve " + str(c) + " has material " + str(d.curve_materials[c]) + " of " + str(d.material_count));
    }
  }
  for (std::size_t i = 0; i < d.vertex_count; ++i) {
    const gpu::VertexBinding& b = d.bindings[i];
    if (b.curve_a >= d.curve_count || b.curve_b >= d.curve_count) {
      return invalid("binding of vertex " + str(i) + " names curves " + str(b.curve_a) + ", " + str(b.curve_b) + " of " +
                     str(d.curve_count));
    }
    if (!std::isfinite(b.w) || !std::isfinite(b.v)) return invalid("binding of vertex " + str(i) + " is not finite");
    for (const gpu::Influence& inf : influenceRow(d, i)) {
      if (!std::isfinite(inf.weight)) return invalid("influence weight of vertex " + str(i) + " is not finite");
      if (inf.weight != 0.0f && inf.bone >= d.bone_count) {
        return invalid("vertex " + str(i) + " is influenced by bone " + str(inf.bone) + " of " + str(d.bone_count));
      }
    }
    for (std::size_t s = 0; s < d.segment_count; ++s) {
      const std::uint32_t r = d.segment_vertices[s * d.vertex_count + i].remainder_index;
      if (r != gpu::kNoRemainder && std::size_t{d.remainder_base[s]} + r >= d.remainders.size()) {
        return invalid("remainder " + str(r) + " of vertex " + str(i) + " in segment " + str(s) + " is out of range");
      }
    }
  }
  return okStatus();
}

// A vertex's place in the sorted order: its pair with a < b (w then weighs b), or a == b with w = 0
// for one curve. (1 - w) S_a + w S_b names the same point either way.
struct SortKey {
  std::uint32_t curve_a;
  std::uint32_t curve_b;
  float w;
  float v;
  std::uint32_t vertex;
};

SortKey sortKey(const gpu::VertexBinding& b, std::uint32_t vertex) {
  if (b.curve_a == b.curve_b || b.w == 0.0f) return {b.curve_a, b.curve_a, 0.0f, b.v, vertex};
  if (b.w == 1.0f) return {b.curve_b, b.curve_b, 0.0f, b.v, vertex};
  if (b.curve_a > b.curve_b) return {b.curve_b, b.curve_a, 1.0f - b.w, b.v, vertex};
  return {b.curve_a, b.curve_b, b.w, b.v, vertex};
}

// Sorted by pair, then by v, so a block's lanes are neighbours along the curve and share bones.
std::vector<SortKey> sortedKeys(const PackedDeformData& d) {
  std::vector<SortKey> keys(d.vertex_count);
  for (std::uint32_t i = 0; i < d.vertex_count; ++i) keys[i] = sortKey(d.bindings[i], i);
  std::sort(keys.begin(), keys.end(), [](const SortKey& x, const SortKey& y) {
    if (x.curve_a != y.curve_a) return x.curve_a < y.curve_a;
    if (x.curve_b != y.curve_b) return x.curve_b < y.curve_b;
    if (x.v != y.v) return x.v < y.v;
    return x.vertex < y.vertex;
  });
  return keys;
}

// Per block: lanes' rows, and which entry of keys each lane copies (padding copies lane 0).
void fillLanes(const PackedDeformData& d, const std::vector<SortKey>& keys, std::size_t b, std::size_t first, Layout& out) {
  const Block& block = out.blocks[b];
  float* rows = out.lane_rows.data() + b * simd_deform::kLaneRows * kBlockLanes;
  for (std::uint32_t l = 0; l < kBlockLanes; ++l) {
    const SortKey& k = keys[first + (l < block.lanes ? l : 0)];
    const double angle = 2.0 * std::numbers::pi * static_cast<double>(k.v);
    const gpu::Float4& x = d.rest_positions[k.vertex];
    rows[simd_deform::kCos * kBlockLanes + l] = static_cast<float>(std::cos(angle));
    rows[simd_deform::kSin * kBlockLanes + l] = static_cast<float>(std::sin(angle));
    rows[simd_deform::kV * kBlockLanes + l] = k.v;
    rows[simd_deform::kW * kBlockLanes + l] = k.w;
    rows[simd_deform::kRestX * kBlockLanes + l] = x.x;
    rows[simd_deform::kRestY * kBlockLanes + l] = x.y;
    rows[simd_deform::kRestZ * kBlockLanes + l] = x.z;
    out.perm[b * kBlockLanes + l] = l < block.lanes ? k.vertex : simd_deform::kPaddingLane;
    for (std::size_t s = 0; s < d.segment_count; ++s) {
      const gpu::SegmentVertex& sv = d.segment_vertices[s * d.vertex_count + k.vertex];
      float* seg = out.segment_rows.data() + (s * out.blocks.size() + b) * simd_deform::kSegmentRows * kBlockLanes;
      gpu::Float4 rem{0.0f, 0.0f, 0.0f, 0.0f};
      if (sv.remainder_index != gpu::kNoRemainder) {
        rem = d.remainders[d.remainder_base[s] + sv.remainder_index];
        out.has_remainder[s * out.blocks.size() + b] = 1;
      }
      seg[simd_deform::kBaseX * kBlockLanes + l] = sv.base_x;
      seg[simd_deform::kBaseY * kBlockLanes + l] = sv.base_y;
      seg[simd_deform::kBaseZ * kBlockLanes + l] = sv.base_z;
      seg[simd_deform::kRemX * kBlockLanes + l] = rem.x;
      seg[simd_deform::kRemY * kBlockLanes + l] = rem.y;
      seg[simd_deform::kRemZ * kBlockLanes + l] = rem.z;
    }
  }
}

// The block's union of bones (sorted), a dense weight row per bone (duplicate entries of a bone in
// one vertex add up, which both LBS and the per-bone sign of DQS allow), and each lane's pivot.
void fillBones(const PackedDeformData& d, const std::vector<SortKey>& keys, std::size_t b, std::size_t first,
               Layout& out) {
  Block& block = out.blocks[b];
  std::vector<std::uint32_t> bones;
  std::array<std::int64_t, kBlockLanes> pivot_bone{};
  for (std::uint32_t l = 0; l < block.lanes; ++l) {
    const std::span<const gpu::Influence> row = influenceRow(d, keys[first + l].vertex);
    pivot_bone[l] = -1;
    float best = 0.0f;
    for (std::size_t k = 0; k < row.size(); ++k) {
      if (row[k].weight != 0.0f) bones.push_back(row[k].bone);
      if (k == 0 || row[k].weight > best) {
        best = row[k].weight;
        pivot_bone[l] = row[k].bone < d.bone_count ? std::int64_t{row[k].bone} : -1;
      }
    }
    if (pivot_bone[l] >= 0) bones.push_back(static_cast<std::uint32_t>(pivot_bone[l]));
  }
  std::sort(bones.begin(), bones.end());
  bones.erase(std::unique(bones.begin(), bones.end()), bones.end());
  block.union_begin = static_cast<std::uint32_t>(out.union_bones.size());
  block.union_count = static_cast<std::uint32_t>(bones.size());
  out.union_bones.insert(out.union_bones.end(), bones.begin(), bones.end());
  out.union_weights.resize(out.union_bones.size() * kBlockLanes, 0.0f);
  auto unionIndex = [&](std::uint32_t bone) {
    return static_cast<std::uint32_t>(std::lower_bound(bones.begin(), bones.end(), bone) - bones.begin());
  };
  for (std::uint32_t l = 0; l < kBlockLanes; ++l) {
    const std::uint32_t source = l < block.lanes ? l : 0;
    for (const gpu::Influence& inf : influenceRow(d, keys[first + source].vertex)) {
      if (inf.weight == 0.0f) continue;
      out.union_weights[(block.union_begin + unionIndex(inf.bone)) * std::size_t{kBlockLanes} + l] += inf.weight;
    }
    const std::int64_t p = pivot_bone[source];
    out.pivots[b * kBlockLanes + l] = p >= 0 ? static_cast<std::int32_t>(unionIndex(static_cast<std::uint32_t>(p))) : 0;
  }
}

void fillCoefficients(const PackedDeformData& d, Layout& out) {
  const std::size_t m_count = d.coefficientsPerCurve();
  auto xyz = [](const std::vector<gpu::Float4>& from, std::vector<float>& to) {
    to.resize(from.size() * 3);
    for (std::size_t k = 0; k < from.size(); ++k) {
      to[3 * k] = from[k].x;
      to[3 * k + 1] = from[k].y;
      to[3 * k + 2] = from[k].z;
    }
  };
  xyz(d.coefficients, out.coefficients);
  if (!d.rates.empty()) xyz(d.rates, out.rates);
  out.curve_modes.assign(std::size_t{d.segment_count} * d.curve_count, 0);
  out.curve_trends.assign(out.curve_modes.size(), 0);
  auto nonzero = [&](std::size_t e) { return out.coefficients[e] != 0.0f || (!out.rates.empty() && out.rates[e] != 0.0f); };
  for (std::size_t sc = 0; sc < out.curve_modes.size(); ++sc) {
    const std::size_t trend = (sc * m_count + m_count - 1) * 3;
    out.curve_trends[sc] = nonzero(trend) || nonzero(trend + 1) || nonzero(trend + 2) ? 1 : 0;
    for (std::uint32_t n = d.modes; n >= 1; --n) {
      bool any = false;
      const std::size_t cos_n = sc * m_count + 2 * static_cast<std::size_t>(n) - 1;  // then sin_n
      for (std::size_t e = 3 * cos_n; e < 3 * (cos_n + 2); ++e) any = any || nonzero(e);
      if (any) {
        out.curve_modes[sc] = n;
        break;
      }
    }
  }
}

std::unique_ptr<Layout> buildLayout(const PackedDeformData& d) {
  auto out = std::make_unique<Layout>();
  out->vertex_count = d.vertex_count;
  out->modes = d.modes;
  out->curve_count = d.curve_count;
  out->material_count = d.material_count;
  out->bone_count = d.bone_count;
  out->segment_count = d.segment_count;
  out->residual_space = d.residual_space;
  out->skinning = d.skinning;
  out->has_rates = !d.rates.empty();
  out->curve_materials = d.curve_materials;
  fillCoefficients(d, *out);

  const std::vector<SortKey> keys = sortedKeys(d);
  std::vector<std::size_t> firsts;  // keys index of each block's lane 0
  for (std::size_t g = 0; g < keys.size();) {
    std::size_t end = g;
    while (end < keys.size() && keys[end].curve_a == keys[g].curve_a && keys[end].curve_b == keys[g].curve_b) ++end;
    for (std::size_t first = g; first < end; first += kBlockLanes) {
      Block block;
      block.curve_a = keys[g].curve_a;
      block.curve_b = keys[g].curve_b;
      block.lanes = static_cast<std::uint32_t>(std::min<std::size_t>(kBlockLanes, end - first));
      out->blocks.push_back(block);
      firsts.push_back(first);
    }
    g = end;
  }
  const std::size_t blocks = out->blocks.size();
  out->lane_rows.assign(blocks * simd_deform::kLaneRows * kBlockLanes, 0.0f);
  out->segment_rows.assign(std::size_t{d.segment_count} * blocks * simd_deform::kSegmentRows * kBlockLanes, 0.0f);
  out->has_remainder.assign(std::size_t{d.segment_count} * blocks, 0);
  out->perm.assign(blocks * kBlockLanes, simd_deform::kPaddingLane);
  out->pivots.assign(blocks * kBlockLanes, 0);
  for (std::size_t b = 0; b < blocks; ++b) {
    fillLanes(d, keys, b, firsts[b], *out);
    fillBones(d, keys, b, firsts[b], *out);
  }
  return out;
}

bool runsOn(CpuKernelArch arch) {
#if ODESKIN_SIMD_X86
  __builtin_cpu_init();
  switch (arch) {
    case CpuKernelArch::kGeneric: return true;
    case CpuKernelArch::kAvx2: return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case CpuKernelArch::kAvx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
             __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("fma");
  }
  return false;
#else
  return arch == CpuKernelArch::kGeneric;
#endif
}

simd_deform::BlockFunctions blockFunctions(CpuKernelArch arch) {
#if ODESKIN_SIMD_X86
  if (arch == CpuKernelArch::kAvx512) return simd_deform::avx512BlockFunctions();
  if (arch == CpuKernelArch::kAvx2) return simd_deform::avx2BlockFunctions();
#endif
  (void)arch;
  return simd_deform::genericBlockFunctions();
}

// Runs fn over every block on `threads` workers (see the header for 0 and 1).
void runBlocks(simd_deform::BlockRangeFn fn, const simd_deform::Frame& frame, std::size_t blocks, unsigned threads) {
  if (threads > 1) threads = usableThreads(threads);
  if (threads == 1 || blocks <= kGrainBlocks) {
    fn(frame, 0, blocks);
    return;
  }
  auto loop = [&] {
    parallelFor(tbb::blocked_range<std::size_t>(0, blocks, kGrainBlocks),
                [&](const tbb::blocked_range<std::size_t>& r) { fn(frame, r.begin(), r.end()); });
  };
  if (threads == 0) {
    loop();
  } else {
    tbb::task_arena arena(static_cast<int>(threads));
    arenaExecute(arena, loop);
  }
}

}  // namespace

const char* cpuKernelArchName(CpuKernelArch arch) {
  switch (arch) {
    case CpuKernelArch::kGeneric: return "generic";
    case CpuKernelArch::kAvx2: return "avx2";
    case CpuKernelArch::kAvx512: return "avx512";
  }
  return "?";
}

std::vector<CpuKernelArch> supportedCpuKernelArchs() {
  std::vector<CpuKernelArch> archs;
  for (CpuKernelArch arch : {CpuKernelArch::kAvx512, CpuKernelArch::kAvx2, CpuKernelArch::kGeneric}) {
    if (runsOn(arch)) archs.push_back(arch);
  }
  return archs;
}

CpuDeformKernel::CpuDeformKernel(std::unique_ptr<const Layout> layout, CpuKernelArch arch)
    : layout_(std::move(layout)), arch_(arch) {}
CpuDeformKernel::CpuDeformKernel(CpuDeformKernel&&) noexcept = default;
CpuDeformKernel& CpuDeformKernel::operator=(CpuDeformKernel&&) noexcept = default;
CpuDeformKernel::~CpuDeformKernel() = default;

Result<CpuDeformKernel> CpuDeformKernel::create(const PackedDeformData& data) {
  std::vector<CpuKernelArch> archs = supportedCpuKernelArchs();
  if (const char* cap = std::getenv("ODESKIN_CPU_KERNEL_ARCH"); cap != nullptr && *cap != '\0') {
    // A misspelt cap would otherwise be ignored, and a benchmark would time the wrong kernel.
    const bool known = std::strcmp(cap, "generic") == 0 || std::strcmp(cap, "avx2") == 0 || std::strcmp(cap, "avx512") == 0;
    if (!known) {
      return invalidArgument(std::string("ODESKIN_CPU_KERNEL_ARCH=") + cap + ": expected generic, avx2 or avx512");
    }
    std::erase_if(archs, [&](CpuKernelArch a) {
      for (CpuKernelArch b : {CpuKernelArch::kGeneric, CpuKernelArch::kAvx2, CpuKernelArch::kAvx512}) {
        if (a == b) return false;
        if (std::strcmp(cap, cpuKernelArchName(b)) == 0) return true;  // a is above the cap
      }
      return false;
    });
  }
  return create(data, archs.front());
}

Result<CpuDeformKernel> CpuDeformKernel::create(const PackedDeformData& data, CpuKernelArch arch) {
  if (!runsOn(arch)) return unavailable(kWho + std::string(cpuKernelArchName(arch)) + " is not supported here");
  ODESKIN_TRY(checkSizes(data));
  ODESKIN_TRY(checkIndices(data));
  return CpuDeformKernel(buildLayout(data), arch);
}

std::uint32_t CpuDeformKernel::vertexCount() const { return layout_->vertex_count; }

CpuDeformKernel::Stats CpuDeformKernel::stats() const {
  const Layout& l = *layout_;
  Stats s;
  s.blocks = l.blockCount();
  // The vector widths simd_deform_blocks.hpp runs a block's lanes at on this instruction set.
  const std::size_t width = arch_ == CpuKernelArch::kAvx512 ? 16 : (arch_ == CpuKernelArch::kAvx2 ? 8 : 4);
  const std::size_t tail = arch_ == CpuKernelArch::kAvx512 ? 8 : width;
  for (const Block& b : l.blocks) {
    s.two_curve_blocks += b.curve_a != b.curve_b ? 1 : 0;
    const std::size_t full = b.lanes / width * width;
    const std::size_t left = b.lanes - full;
    s.lanes += full + (left == 0 ? 0 : (left <= tail ? tail : width));
  }
  s.mean_union_bones = s.blocks ? static_cast<double>(l.union_bones.size()) / static_cast<double>(s.blocks) : 0.0;
  s.bytes = sizeof(Layout) + l.blocks.size() * sizeof(Block) +
            (l.lane_rows.size() + l.segment_rows.size() + l.union_weights.size() + l.coefficients.size() +
             l.rates.size()) * sizeof(float) +
            (l.perm.size() + l.union_bones.size() + l.pivots.size() + l.curve_materials.size() + l.curve_modes.size()) *
                sizeof(std::uint32_t) +
            l.has_remainder.size() + l.curve_trends.size();
  return s;
}

Status CpuDeformKernel::deform(std::uint32_t segment, std::span<const gpu::BoneMatrix> bones,
                               std::span<const gpu::ModeBasis> basis, std::span<gpu::Float4> out_positions,
                               unsigned threads) const {
  return run(true, segment, bones, {}, basis, out_positions, threads);
}

Status CpuDeformKernel::deform(std::uint32_t segment, std::span<const gpu::BoneMatrix> bones,
                               std::span<const gpu::DualQuat> dual_quats, std::span<const gpu::ModeBasis> basis,
                               std::span<gpu::Float4> out_positions, unsigned threads) const {
  if (layout_->skinning == SkinningMode::kDualQuaternion && dual_quats.size() != layout_->bone_count) {
    return invalid("dual_quats has " + str(dual_quats.size()) + " entries, expected " + str(layout_->bone_count));
  }
  return run(true, segment, bones, dual_quats, basis, out_positions, threads);
}

Status CpuDeformKernel::skin(std::span<const gpu::BoneMatrix> bones, std::span<gpu::Float4> out_positions,
                             unsigned threads) const {
  return run(false, 0, bones, {}, {}, out_positions, threads);
}

Status CpuDeformKernel::skin(std::span<const gpu::BoneMatrix> bones, std::span<const gpu::DualQuat> dual_quats,
                             std::span<gpu::Float4> out_positions, unsigned threads) const {
  if (layout_->skinning == SkinningMode::kDualQuaternion && dual_quats.size() != layout_->bone_count) {
    return invalid("dual_quats has " + str(dual_quats.size()) + " entries, expected " + str(layout_->bone_count));
  }
  return run(false, 0, bones, dual_quats, {}, out_positions, threads);
}

Status CpuDeformKernel::run(bool deform, std::uint32_t segment, std::span<const gpu::BoneMatrix> bones,
                            std::span<const gpu::DualQuat> dual_quats, std::span<const gpu::ModeBasis> basis,
                            std::span<gpu::Float4> out_positions, unsigned threads) const {
  const Layout& l = *layout_;
  if (deform && segment >= l.segment_count) return invalid("segment " + str(segment) + " of " + str(l.segment_count));
  if (bones.size() != l.bone_count) {
    return invalid("bones has " + str(bones.size()) + " entries, expected " + str(l.bone_count));
  }
  const std::size_t basis_entries = ODESKIN_BASIS_ENTRIES(std::size_t{l.material_count}, std::size_t{l.modes});
  if (deform && basis.size() != basis_entries) {
    return invalid("basis has " + str(basis.size()) + " entries, expected material_count x (N+1) + 1 = " +
                   str(basis_entries));
  }
  if (out_positions.size() != l.vertex_count) {
    return invalid("out_positions has " + str(out_positions.size()) + " entries, expected " + str(l.vertex_count));
  }
  simd_deform::Frame frame;
  frame.layout = &l;
  frame.segment = segment;
  frame.bones = bones.data();
  frame.basis = basis.data();
  frame.out_positions = out_positions.data();
  // cppcheck-suppress variableScope ; frame.dual_quats points into it until runBlocks below returns
  std::array<gpu::DualQuat, kMaxStackBones> stack_dual_quats;
  std::vector<gpu::DualQuat> heap_dual_quats;
  if (l.skinning == SkinningMode::kDualQuaternion) {
    if (dual_quats.empty()) {
      std::span<gpu::DualQuat> converted;
      if (bones.size() > kMaxStackBones) {
        heap_dual_quats.resize(bones.size());
        converted = heap_dual_quats;
      } else {
        converted = std::span(stack_dual_quats.data(), bones.size());
      }
      toGpuDualQuaternions(bones, converted);
      dual_quats = converted;
    }
    frame.dual_quats = dual_quats.data();
  }
  const simd_deform::BlockFunctions fns = blockFunctions(arch_);
  runBlocks(deform ? fns.deform : fns.skin, frame, l.blockCount(), threads);
  return okStatus();
}

}  // namespace odeskin
