// SPDX-License-Identifier: MIT
// GPU layout of the instanced runtime (shaders/instanced_deform.comp, shaders/instance_normals.comp),
// read by C++ (engine/runtime, host/runtime) and GLSL, in the subset both understand, like
// engine/core/gpu_layout.h whose structs it reuses. runtime_layout.hpp checks sizes and offsets.
#ifndef ODESKIN_RUNTIME_LAYOUT_H
#define ODESKIN_RUNTIME_LAYOUT_H

#include "../core/gpu_layout.h"

#ifdef __cplusplus
namespace odeskin::gpu {
#endif

// instanced_deform.comp, descriptor set 0. Bindings 0-8 are gpu_layout.h's asset arrays, uploaded
// once; ODESKIN_BINDING_RATES holds every material preset's rates back to back (preset p's start at// instance_tangents.comp, descriptor set 0 (RuntimeOptions::tangents; outputs in the output vertices:
// render vertices with a render layout, else the topology's).
#define ODESKIN_RT_TANGENTS_BINDING_POSITIONS 0      // Float4[capacity * V]: the slot's deformed positions
#define ODESKIN_RT_TANGENTS_BINDING_NORMALS 1        // Float4[capacity * O]: the output vertices' normals
#define ODESKIN_RT_TANGENTS_BINDING_CORNER_OFFSETS 2 // uint[V + 1], as for the normals
#define ODESKIN_RT_TANGENTS_BINDING_CORNERS 3        // Corner[offsets[V]]
#define ODESKIN_RT_TANGENTS_BINDING_TOPOLOGY 4       // uint[R]: output vertex o is topology vertex topology[o] (a stand-in without a render layout)
#define ODESKIN_RT_TANGENTS_BINDING_FRAMES 5         // TangentFrame[O]
#define ODESKIN_RT_TANGENTS_BINDING_WEIGHTS 6        // TangentWeights[]: frame o's at frames[o].weights, one per corner of its topology vertex
#define ODESKIN_RT_TANGENTS_BINDING_OUT_TANGENTS 7   // Float4[capacity * O]: unit tangent xyz, w = handedness

// InstanceRecord::rates_offset). Per frame slot, in the slot's mapped input buffer:
#define ODESKIN_RT_BINDING_BONES 9              // BoneMatrix[instances * bone_count]: instance k's at k * B
#define ODESKIN_RT_BINDING_MODE_BASIS 10        // ModeBasis[instances * basis_entries]: instance k's at k * E
#define ODESKIN_RT_BINDING_BONE_DUAL_QUATS 12   // DualQuat[instances * bone_count] (dual-quaternion skinning)
#define ODESKIN_RT_BINDING_INSTANCES 13         // InstanceRecord[instances]
// Per frame slot, written by the GPU:
#define ODESKIN_RT_BINDING_OUT_POSITIONS 11     // Float4[capacity * V]: instance k's vertex i at k * V + i, w = 1
#define ODESKIN_RT_BINDING_BOUNDS 14            // BoundsKeys[capacity]

// instance_normals.comp, descriptor set 0: over the topology's vertices, or (RenderCorners, hard
// edges) over the render vertices, whose corner lists then are per render vertex.
#define ODESKIN_RT_NORMALS_BINDING_POSITIONS 0      // Float4[capacity * V]: the slot's deformed positions
#define ODESKIN_RT_NORMALS_BINDING_CORNER_OFFSETS 1 // uint[V + 1]: vertex i's corners are [offsets[i], offsets[i+1])
#define ODESKIN_RT_NORMALS_BINDING_CORNERS 2        // Corner[offsets[V]]
#define ODESKIN_RT_NORMALS_BINDING_OUT_NORMALS 3    // Float4[capacity * V]: unit normal xyz, w = 0
#define ODESKIN_RT_NORMALS_BINDING_TOPOLOGY 4       // uint[R]: with render_layout = 1, vertex r's own position is topology[r]
// render_gather.comp, descriptor set 0 (RuntimeOptions::render_layout with a glTF asset's render vertices).
#define ODESKIN_RT_GATHER_BINDING_POSITIONS 0       // Float4[capacity * V]: the slot's deformed positions
#define ODESKIN_RT_GATHER_BINDING_NORMALS 1         // Float4[capacity * V]: its normals (the positions again without)
#define ODESKIN_RT_GATHER_BINDING_TOPOLOGY 2        // uint[R]: render vertex r is topology vertex topology[r]
#define ODESKIN_RT_GATHER_BINDING_OUT_POSITIONS 3   // Float4[capacity * R]: instance k's render vertex r at k * R + r
#define ODESKIN_RT_GATHER_BINDING_OUT_NORMALS 4     // Float4[capacity * R] (the out positions again without normals)

// InstanceRecord::rates_offset of an instance whose preset carries no rates (all zero).
#define ODESKIN_RT_NO_RATES 0xFFFFFFFFu

// What one instance plays this frame; bone, basis and output ranges follow from its index.
struct InstanceRecord {
  uint segment;         // s < segment_count
  uint remainder_base;  // first remainder of segment s in remainders[]
  uint rates_offset;    // first rate of the instance's preset in rates[], or ODESKIN_RT_NO_RATES
  uint preset;          // material preset (the CPU backend picks its packed data by it)
};

// One triangle around vertex i: the triangle is (i, next, prev) counter-clockwise, and contributes
// cross(p[next] - p[i], p[prev] - p[i]) (twice its area times its unit normal) to i's normal.
struct Corner {
  uint next;
  uint prev;
};

// Output vertex o's bind tangent as weights on its topology vertex's corner edges: the deformed
// tangent is sum over corners c of next * (p[c.next] - p[i]) + prev * (p[c.prev] - p[i]), the
// least-squares deformation gradient of the one-ring applied to the bind tangent (instance_tangents.hpp).
struct TangentFrame {
  uint weights;      // first TangentWeights entry; one per corner of the topology vertex
  float handedness;  // +1 or -1: the bitangent is handedness * cross(normal, tangent) (glTF TANGENT.w)
};

struct TangentWeights {
  float next;
  float prev;
};

// Per-instance bounding box as order-preserving unsigned keys of floats (orderedKey in
// runtime_layout.hpp and instanced_deform.comp), so atomicMin orders them as floats. keys[0..2]
// hold the minimum x, y, z and keys[4..6] the minimum of -x, -y, -z (that is, -max): one fill value
// (0xFFFFFFFF, the key above +inf) resets the whole buffer and one atomic operation serves both.
struct BoundsKeys {
  uint keys[8];
};

// Push constants of instanced_deform.comp. The fields shaders/deform_vertex.glsl and
// shaders/skinning.glsl read have DeformPushConstants' names.
struct InstancedPushConstants {
  uint vertex_count;      // V
  uint instance_count;    // instances this frame (the dispatch's y extent)
  uint modes;             // N
  uint curve_count;       // C
  uint material_count;
  uint bone_count;        // B, per instance
  uint influence_layout;  // ODESKIN_INFLUENCES_SPARSE, 4 or 8
  uint residual_space;    // ODESKIN_RESIDUAL_BIND or ODESKIN_RESIDUAL_POSED
  uint skinning;          // ODESKIN_SKINNING_LINEAR or ODESKIN_SKINNING_DUAL_QUATERNION
  uint basis_entries;     // E = ODESKIN_BASIS_ENTRIES(material_count, modes), per instance
  uint pad0;
  uint pad1;
};

struct NormalsPushConstants {
  uint vertex_count;    // normals per instance (the corner lists' vertices)
  uint instance_count;
  uint position_count;  // V: positions per instance
  uint render_layout;   // 1: normal r's own position is topology[r]; 0: position r
};

struct GatherPushConstants {
  uint vertex_count;    // V
  uint render_count;    // R
  uint instance_count;
  uint normals;         // 1: gather the normals too
};

struct TangentsPushConstants {
  uint vertex_count;    // V
  uint output_count;    // O: R with a render layout, else V
  uint instance_count;
  uint render_layout;   // 1: output vertex o is topology vertex topology[o]; 0: o itself
};

#ifdef __cplusplus
}  // namespace odeskin::gpu
#endif

#endif  // ODESKIN_RUNTIME_LAYOUT_H
