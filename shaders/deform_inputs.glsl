// SPDX-License-Identifier: MIT
// The read-only inputs of fourier_deform.comp, lbs.comp and instanced_deform*.comp, and the fetches
// that turn them back into gpu_layout.h's structs. Two builds of each shader read them two ways:
//  - uniform texel buffers (host/texel_bindings.hpp gives each one's format), the default: lavapipe
//    loads a storage buffer lane by lane and component by component, each behind a branch, but
//    fetches a whole texel per lane in one gather (docs/performance.md, "Lavapipe");
//  - with ODESKIN_STORAGE_INPUTS, storage buffers of the same element types, which a GPU reads
//    through its load units rather than its texture units (docs/performance.md, "On a GPU").
// The host picks the build (host/shader_inputs.hpp). The runtime's bones, basis and dual
// quaternions use the same binding numbers as the single mesh's (static_assert in
// texel_bindings.hpp). Include gpu_layout.h first.

#ifdef ODESKIN_STORAGE_INPUTS
#define ODESKIN_INPUT(binding_, block_, element_, name_) \
  layout(std430, set = 0, binding = binding_) readonly buffer block_ { element_ name_[]; };
#define ODESKIN_FETCH(name_, k) name_[k]
#else
#define ODESKIN_INPUT(binding_, block_, element_, name_) \
  layout(set = 0, binding = binding_) uniform element_##Texels name_;
#define ODESKIN_FETCH(name_, k) texelFetch(name_, int(k))
// The texel buffer type that returns each element type.
#define vec4Texels samplerBuffer
#define vec2Texels samplerBuffer
#define uvec4Texels usamplerBuffer
#define uvec2Texels usamplerBuffer
#define uintTexels usamplerBuffer
#endif

ODESKIN_INPUT(ODESKIN_BINDING_REST_POSITIONS, RestPositions, vec4, rest_positions)              // Float4
ODESKIN_INPUT(ODESKIN_BINDING_VERTEX_BINDINGS, VertexBindings, uvec4, bindings)                 // VertexBinding
ODESKIN_INPUT(ODESKIN_BINDING_SEGMENT_VERTICES, SegmentVertices, uvec4, segment_vertices)       // SegmentVertex
ODESKIN_INPUT(ODESKIN_BINDING_REMAINDERS, Remainders, vec4, remainders)                         // Float4
ODESKIN_INPUT(ODESKIN_BINDING_INFLUENCE_OFFSETS, InfluenceOffsets, uint, influence_offsets)     // uint
ODESKIN_INPUT(ODESKIN_BINDING_INFLUENCES, Influences, uvec2, influences)                        // Influence
ODESKIN_INPUT(ODESKIN_BINDING_BONES, Bones, vec4, bones)                                        // BoneMatrix: 3 rows
ODESKIN_INPUT(ODESKIN_BINDING_MODE_BASIS, ModeBases, vec2, basis)                               // ModeBasis
ODESKIN_INPUT(ODESKIN_BINDING_BONE_DUAL_QUATS, BoneDualQuats, vec4, bone_dual_quats)            // DualQuat: 2 entries
ODESKIN_INPUT(ODESKIN_BINDING_FOLDED_SERIES, FoldedSeries, vec4, folded_series)                 // Float4

vec3 restPosition(uint i) { return ODESKIN_FETCH(rest_positions, i).xyz; }

VertexBinding vertexBinding(uint i) {
  uvec4 t = uvec4(ODESKIN_FETCH(bindings, i));
  return VertexBinding(t.x, t.y, uintBitsToFloat(t.z), uintBitsToFloat(t.w));
}

SegmentVertex segmentVertex(uint k) {
  uvec4 t = uvec4(ODESKIN_FETCH(segment_vertices, k));
  return SegmentVertex(uintBitsToFloat(t.x), uintBitsToFloat(t.y), uintBitsToFloat(t.z), t.w);
}

vec3 remainder(uint k) { return ODESKIN_FETCH(remainders, k).xyz; }
vec3 foldedCoefficient(uint k) { return ODESKIN_FETCH(folded_series, k).xyz; }
uint influenceOffset(uint i) { return uint(ODESKIN_FETCH(influence_offsets, i)); }

Influence influence(uint k) {
  uvec2 t = uvec2(ODESKIN_FETCH(influences, k));
  return Influence(t.x, uintBitsToFloat(t.y));
}

// Row r (0..2) of bone b's 3x4 matrix.
vec4 boneRow(uint b, uint r) { return ODESKIN_FETCH(bones, 3u * b + r); }

ModeBasis modeBasis(uint k) {
  vec2 t = vec2(ODESKIN_FETCH(basis, k));
  return ModeBasis(t.x, t.y);
}

vec4 dualQuatReal(uint b) { return ODESKIN_FETCH(bone_dual_quats, 2u * b); }
vec4 dualQuatDual(uint b) { return ODESKIN_FETCH(bone_dual_quats, 2u * b + 1u); }
