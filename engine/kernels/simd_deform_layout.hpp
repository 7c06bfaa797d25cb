// SPDX-License-Identifier: MIT
// The reorganised data of CpuDeformKernel (cpu_deform_kernel.hpp) and the per-frame parameters
// its SIMD block loops read. Internal to the kernel: built once by CpuDeformKernel::create, read by
// simd_deform_blocks.hpp, which cpu_deform_kernel_simd.cpp compiles once per instruction set.
//
// Vertices are sorted by their curve pair (a, b) and cut into blocks of kBlockLanes lanes. Every
// lane of a block shares (a, b), so the series' coefficients are broadcast scalars instead of
// per-lane gathers, and one block's vertices lie between the same two iso-curves, so they are
// skinned by few bones: each block keeps the union of its lanes' bones with a dense weight row per
// bone (zero where a lane does not use it), and skinning costs 12 multiply-adds per union bone.
// The last block of a pair is padded with copies of its first lane; padded lanes are computed and
// never written.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#include "../core/gpu_layout.hpp"
#include "../core/types.hpp"

namespace odeskin::simd_deform {

// 16 floats: one AVX-512 register, two AVX2 registers, four SSE/NEON registers.
inline constexpr std::uint32_t kBlockLanes = 16;
// Folded coefficients of one curve fit on the stack up to this N (FourierDeformJob's limit too).
inline constexpr std::uint32_t kMaxModes = 64;
inline constexpr std::uint32_t kMaxCurveFloats = (2 * kMaxModes + 2) * 3;
// perm entry of a padded lane.
inline constexpr std::uint32_t kPaddingLane = 0xFFFFFFFFu;

// Rows of kBlockLanes floats per block, in this order: cos(2 pi v), sin(2 pi v) (computed in
// double), v, w of the pair (a, b), rest position x, y, z.
enum LaneRow : std::uint32_t { kCos, kSin, kV, kW, kRestX, kRestY, kRestZ, kLaneRows };
// Rows per (segment, block): the base residual r^s and the sparse remainder (zero where none).
enum SegmentRow : std::uint32_t { kBaseX, kBaseY, kBaseZ, kRemX, kRemY, kRemZ, kSegmentRows };
// Where row `row` of a block starts, in floats from the block's first (a pointer offset, so size_t).
constexpr std::size_t rowOffset(std::uint32_t row) { return std::size_t{row} * kBlockLanes; }

template <typename T>
struct AlignedAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};  // a cache line and one AVX-512 register
  AlignedAllocator() = default;
  template <typename U>
  AlignedAllocator(const AlignedAllocator<U>&) {}  // cppcheck-suppress noExplicitConstructor ; NOLINT: rebinding, as std::allocator does
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlignment); }
  template <typename U>
  bool operator==(const AlignedAllocator<U>&) const { return true; }
};
template <typename T>
using AlignedVector = std::vector<T, AlignedAllocator<T>>;

struct Block {
  std::uint32_t curve_a = 0;
  std::uint32_t curve_b = 0;       // == curve_a: one curve, w ignored
  std::uint32_t union_begin = 0;   // first entry in Layout::union_bones / union_weights rows
  std::uint32_t union_count = 0;
  std::uint32_t lanes = 0;         // valid lanes, 1..kBlockLanes; the rest are padding
};

struct Layout {
  std::uint32_t vertex_count = 0;
  std::uint32_t modes = 0;  // N
  std::uint32_t curve_count = 0;
  std::uint32_t material_count = 0;
  std::uint32_t bone_count = 0;
  std::uint32_t segment_count = 0;
  ResidualSpace residual_space = ResidualSpace::kBind;
  SkinningMode skinning = SkinningMode::kLinear;
  bool has_rates = false;

  std::vector<Block> blocks;
  AlignedVector<float> lane_rows;         // blocks x kLaneRows x kBlockLanes
  AlignedVector<float> segment_rows;      // segment_count x blocks x kSegmentRows x kBlockLanes
  std::vector<std::uint8_t> has_remainder;  // segment_count x blocks: any lane with a remainder
  std::vector<std::uint32_t> perm;        // blocks x kBlockLanes: mesh vertex of each lane
  std::vector<std::uint32_t> union_bones; // per block, union_count bone indices from union_begin
  AlignedVector<float> union_weights;     // union_bones.size() x kBlockLanes
  // Dual-quaternion skinning only: per lane, the union entry (0..union_count-1) of the bone whose
  // weight is the first largest in the vertex's row (the antipodality pivot of Kavan's blend).
  AlignedVector<std::int32_t> pivots;     // blocks x kBlockLanes
  // Per (segment, curve), 2N+2 entries of xyz: the gpu_layout.h coefficient order, w dropped.
  std::vector<float> coefficients;        // segment_count x curve_count x (2N+2) x 3
  std::vector<float> rates;               // same shape, empty without rates
  std::vector<std::uint32_t> curve_materials;  // curve_count
  // Per (segment, curve): the highest harmonic n with a non-zero coefficient or rate (0: none), so
  // the series stops early on curves whose high modes vanish.
  std::vector<std::uint32_t> curve_modes;  // segment_count x curve_count
  // Per (segment, curve): 1 if the open-curve trend (coefficient or rate 2N+1) is non-zero.
  std::vector<std::uint8_t> curve_trends;  // segment_count x curve_count

  std::size_t blockCount() const { return blocks.size(); }
  std::uint32_t coefficientsPerCurve() const { return 2 * modes + 2; }
};

// One call's inputs, validated by CpuDeformKernel before any block runs.
struct Frame {
  const Layout* layout = nullptr;
  std::uint32_t segment = 0;
  const gpu::BoneMatrix* bones = nullptr;
  const gpu::DualQuat* dual_quats = nullptr;  // dual-quaternion skinning only
  const gpu::ModeBasis* basis = nullptr;      // deform only
  gpu::Float4* out_positions = nullptr;
};

// Blocks [begin, end) of one frame: deformation + skinning, or skinning alone.
using BlockRangeFn = void (*)(const Frame& frame, std::size_t begin, std::size_t end);

struct BlockFunctions {
  BlockRangeFn deform = nullptr;
  BlockRangeFn skin = nullptr;
};

// One entry per instruction set compiled into cpu_deform_kernel_simd.cpp. The x86 ones exist only
// in x86-64 builds, and CpuDeformKernel picks them only where the CPU runs them.
BlockFunctions genericBlockFunctions();
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define ODESKIN_SIMD_X86 1
BlockFunctions avx2BlockFunctions();
BlockFunctions avx512BlockFunctions();
#endif

}  // namespace odeskin::simd_deform
