// SPDX-License-Identifier: MIT
// GPU buffer layouts, binding numbers and push constants, read by both C++ (host/, engine fast path)
// and GLSL (shaders/*.comp, via #include). Written in the subset both languages understand; the
// C++ side checks sizes and offsets with static_asserts in gpu_layout.hpp. std430 rules apply:
// every struct here is built from 4-byte scalars (no vec3) so C++ and GLSL agree without padding.
#ifndef ODESKIN_GPU_LAYOUT_H
#define ODESKIN_GPU_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
namespace odeskin::gpu {
using uint = std::uint32_t;
#endif

// 64 threads: a multiple of every subgroup size we meet (lavapipe 8, NVIDIA 32, AMD 64).
#define ODESKIN_WORKGROUP_SIZE 64

// Marks a vertex that has no sparse remainder in the current segment.
#define ODESKIN_NO_REMAINDER 0xFFFFFFFFu

// Influence layouts (push constant `influence_layout`): 0 = compressed sparse rows
// (influence_offsets[V+1] into influences[]), 4 or 8 = fixed slots per vertex (zero-weight padding).
#define ODESKIN_INFLUENCES_SPARSE 0u

// Where the residual is applied (push constant `residual_space`), PIPELINE.md sections 3 and 6.
#define ODESKIN_RESIDUAL_BIND 0u
#define ODESKIN_RESIDUAL_POSED 1u

// How bones deform a vertex (push constant `skinning`, SkinningMode in types.hpp): linear blend
// skinning from BoneMatrix rows, or dual-quaternion skinning (Kavan et al. 2008) from DualQuat.
#define ODESKIN_SKINNING_LINEAR 0u
#define ODESKIN_SKINNING_DUAL_QUATERNION 1u
// Dual-quaternion blends whose real part is not longer than this are skinned by LBS instead
// (kMinDualQuaternionBlendNorm in engine/kernels/dual_quaternion.hpp explains why none should be).
#define ODESKIN_DQS_MIN_BLEND_NORM 1e-6

// Descriptor set 0 bindings of fourier_deform.comp and lbs.comp.
#define ODESKIN_BINDING_REST_POSITIONS 0     // Float4[V]: xyz rest position, w unused
#define ODESKIN_BINDING_VERTEX_BINDINGS 1    // VertexBinding[V]
#define ODESKIN_BINDING_SEGMENT_VERTICES 2   // SegmentVertex[S*V]
#define ODESKIN_BINDING_REMAINDERS 3         // Float4[total remainders]
#define ODESKIN_BINDING_CURVE_MATERIALS 4    // uint[C]
#define ODESKIN_BINDING_COEFFICIENTS 5       // Float4[S*C*M], M = 2N+2 (see below)
#define ODESKIN_BINDING_RATES 6              // Float4[S*C*M]
#define ODESKIN_BINDING_INFLUENCE_OFFSETS 7  // uint[V+1] (sparse layout only)
#define ODESKIN_BINDING_INFLUENCES 8         // Influence[...]
#define ODESKIN_BINDING_BONES 9              // per frame: BoneMatrix[bone_count]
#define ODESKIN_BINDING_MODE_BASIS 10        // per frame: ModeBasis[material_count * (N+1)]
#define ODESKIN_BINDING_OUT_POSITIONS 11     // Float4[V]: deformed xyz, w = 1
// Per frame: DualQuat[bone_count], the same bones as ODESKIN_BINDING_BONES as unit dual quaternions
// (toGpuDualQuaternions in engine/kernels/packed_deform.hpp, computed on the host from the
// BoneMatrix rows). A second buffer rather than columns of BoneMatrix: LBS keeps its 48-byte
// rows, and the slice is always bound but only written and read with ODESKIN_SKINNING_DUAL_QUATERNION.
#define ODESKIN_BINDING_BONE_DUAL_QUATS 12
// Float4[D*C*M]: the frame's time basis folded into every curve's coefficients by fold_series.comp,
// A_cm = gamma_n(m) d_cm + psi_n(m) rdot_cm, for each of the D deformations of a dispatch (one mesh:
// D = 1; the runtime: one per instance), deformation k's curve c entry m at (k C + c) M + m.
// Written by the fold pass, read by the deformation shaders. (13 and 14 are runtime_layout.h's.)
#define ODESKIN_BINDING_FOLDED_SERIES 15

// Shaders declare the Float4 arrays they write as vec4 (the same std430 layout): a store to a struct
// element is a store per member through nested access chains, which the Khronos layer's
// synchronization validation (1.3.239) does not count as a write, so a missing barrier went unseen.
struct Float4 {
  float x;
  float y;
  float z;
  float w;
};

// Iso-parametric curve binding of one vertex: it evaluates (1 - w) series_a(v) + w series_b(v).
struct VertexBinding {
  uint curve_a;
  uint curve_b;
  float w;
  float v;
};

// Per segment and vertex: the bind-space corrective r^s of the segment's start pose, and the index
// of the vertex's sparse remainder in this segment (ODESKIN_NO_REMAINDER if none).
struct SegmentVertex {
  float base_x;
  float base_y;
  float base_z;
  uint remainder_index;
};

struct Influence {
  uint bone;
  float weight;
};

// Rigid or affine bone transform, bind space -> posed space, as three rows of a 3x4 matrix.
struct BoneMatrix {
  Float4 row0;
  Float4 row1;
  Float4 row2;
};

// Unit dual quaternion real + eps dual of a rigid bone transform, each stored (x, y, z, w): for
// x -> R x + t, real is R's quaternion and dual = 1/2 (0, t) real.
struct DualQuat {
  Float4 real;
  Float4 dual;
};

// Time basis of one (material, mode n) pair at the frame's tau: a_n = gamma d_n + psi rate_n.
struct ModeBasis {
  float gamma;
  float psi;
};

// Time basis per frame: material_count x (N+1) entries (gamma_n, psi_n) of every (material, mode),
// then ONE more entry whose gamma is the sparse remainders' weight w(tau) = 3 tau^2 - 2 tau^3
// (MATH.md 4.4 allows any w with w(0) = 0, w(1) = 1; this one has zero rate at both ends, so the
// remainders never break the C1 join between segments). ODESKIN_BASIS_ENTRIES gives the count.
#define ODESKIN_BASIS_ENTRIES(material_count, modes) ((material_count) * ((modes) + 1u) + 1u)

// Coefficient layout per curve, M = 2N + 2 entries: m = 0 constant, m = 2n-1 cos(2 pi n v),
// m = 2n sin(2 pi n v) for n = 1..N (MATH.md 4.2 order), m = 2N+1 the open-curve trend v (MATH.md
// 4.3; zero on closed curves). The trend and the constant follow mode n = 0.

// Push constants (<= 128 bytes, the guaranteed minimum and lavapipe's limit).
struct DeformPushConstants {
  uint vertex_count;
  uint modes;              // N
  uint curve_count;        // C
  uint material_count;
  uint bone_count;
  uint segment;            // s: selects segment_vertices[s*V..] and coefficients[s*C*M..]
  uint remainder_base;     // first remainder of segment s in remainders[]
  uint influence_layout;   // ODESKIN_INFLUENCES_SPARSE, 4 or 8
  uint residual_space;     // ODESKIN_RESIDUAL_BIND or ODESKIN_RESIDUAL_POSED
  uint use_rates;          // 0: rates buffer ignored
  uint skinning;           // ODESKIN_SKINNING_LINEAR or ODESKIN_SKINNING_DUAL_QUATERNION
  uint pad1;
};

// Push constants of fold_series.comp, whose invocation (x, y) folds entry x = c M + m of deformation y.
struct FoldPushConstants {
  uint modes;          // N
  uint curve_count;    // C
  uint basis_entries;  // E = ODESKIN_BASIS_ENTRIES(material_count, modes): deformation y's basis at y E
  uint pad0;
};

#ifdef __cplusplus
}  // namespace odeskin::gpu
#endif

#endif  // ODESKIN_GPU_LAYOUT_H
