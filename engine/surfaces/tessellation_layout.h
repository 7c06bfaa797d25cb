// SPDX-License-Identifier: MIT
// Buffers, bindings and push constants of shaders/ode6_tessellate.comp, read by both C++
// (engine/surfaces/tessellation_gpu.*, host/surface_tessellator.*) and GLSL (via #include). Written in
// the subset both languages understand; every struct is made of 4-byte scalars so std430 and C++
// agree without padding (sizes checked in tessellation_gpu.hpp).
#ifndef ODESKIN_SURFACES_TESSELLATION_LAYOUT_H
#define ODESKIN_SURFACES_TESSELLATION_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
namespace odeskin::gpu {
using uint = std::uint32_t;
#endif

#define ODESKIN_TESSELLATE_WORKGROUP_SIZE 64
// Largest workgroup count of one dispatch (the guaranteed maxComputeWorkGroupCount[0]); larger grids
// are dispatched in pieces that differ in TessellatePushConstants::first_item.
#define ODESKIN_TESSELLATE_MAX_GROUPS 65535u

// Power-series terms of the kSeries branch, as kOde6SeriesTerms in ode6_cardinal.hpp.
#define ODESKIN_ODE6_SERIES_TERMS 40

// Branches of Ode6Basis (ode6_cardinal.hpp).
#define ODESKIN_ODE6_SERIES 0u
#define ODESKIN_ODE6_REAL 1u
#define ODESKIN_ODE6_PQ 2u

// The two passes of one tessellation, in one command buffer with a barrier between them. The pass
// is a specialization constant (constant_id ODESKIN_TESSELLATE_PASS_CONSTANT_ID), not a push
// constant: two pipelines, each compiled without the other pass's code (on lavapipe the vertex
// pass took 661 ms instead of 400 ms for 2M vertices, in one measurement on a loaded machine, with
// the cardinal code merely present behind a uniform branch).
#define ODESKIN_TESSELLATE_PASS_CONSTANT_ID 0
#define ODESKIN_TESSELLATE_PASS_CARDINALS 0u  // one invocation per (cardinal set, u sample): g_1..g_6
#define ODESKIN_TESSELLATE_PASS_POSITIONS 1u  // one invocation per vertex of the welded grid

// Descriptor set 0.
#define ODESKIN_TESSELLATE_BINDING_CARDINALS 0         // Ode6GpuCardinal[cardinal_count]
#define ODESKIN_TESSELLATE_BINDING_PATCH_CARDINALS 1   // uint[rows * columns]: cardinal set of each patch
// vec4[boundary_count * 3 * grid_columns]: S, S_u, S_uu (k = 0, 1, 2) of boundary b at grid column j
// at [(3 b + k) grid_columns + j]; xyz used, w = 0.
#define ODESKIN_TESSELLATE_BINDING_BOUNDARY_SAMPLES 2
// float[cardinal_count * u_samples * 6]: written by the first pass, g_k(u_i) at [(set u_samples + i) 6 + k - 1].
#define ODESKIN_TESSELLATE_BINDING_TABLE 3
#define ODESKIN_TESSELLATE_BINDING_OUT_POSITIONS 4     // vec4[grid_rows * grid_columns]: xyz, w = 1

// One set of cardinal functions (Ode6Basis): the branch, its parameters, and the 3x3 matrices that
// turn each block's basis functions into block-cardinal functions, row-major: even[3 l + i].
struct Ode6GpuCardinal {
  uint branch;  // ODESKIN_ODE6_*
  float b;      // eta / rho
  float c;      // lambda / rho
  float x1;     // real: s1; pq: X1
  float x2;     // real: s2; pq: X2
  float w;      // row scale W (informative: already folded into even/odd)
  float reserved0;
  float reserved1;
  float even[9];
  float odd[9];
};

// 48 bytes (<= 128, every device's minimum).
struct TessellatePushConstants {
  uint first_item;      // index of this dispatch's first invocation's item (vertex or table entry)
  uint item_count;      // items of this pass in total
  uint rows;            // patch rows
  uint columns;         // patch columns
  uint u_samples;       // per patch, >= 2
  uint v_samples;       // per patch, >= 2
  uint grid_columns;    // columns of the welded grid
  uint boundary_count;  // boundaries (row r joins r and (r + 1) mod boundary_count)
  uint reserved0;
  uint reserved1;
  uint reserved2;
  uint reserved3;
};

#ifdef __cplusplus
}  // namespace odeskin::gpu
#endif

#endif  // ODESKIN_SURFACES_TESSELLATION_LAYOUT_H
