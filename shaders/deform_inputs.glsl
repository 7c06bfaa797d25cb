// SPDX-License-Identifier: MIT
// The read-only inputs of fourier_deform.comp, lbs.comp and instanced_deform*.comp as uniform
// texel buffers (host/texel_bindings.hpp gives each one's format), and the fetches that turn
// texels back into gpu_layout.h's structs. Texel buffers rather than storage buffers because
// lavapipe loads a storage buffer lane by lane and component by component, each behind a branch,
// but fetches a whole texel per lane in one gather (docs/performance.md, "Lavapipe"); a GPU reads
// either through its caches. The runtime's bones, basis and dual quaternions use the same binding
// numbers as the single mesh's (static_assert in texel_bindings.hpp). Include gpu_layout.h first.

layout(set = 0, binding = ODESKIN_BINDING_REST_POSITIONS) uniform samplerBuffer rest_positions;      // Float4
layout(set = 0, binding = ODESKIN_BINDING_VERTEX_BINDINGS) uniform usamplerBuffer bindings;          // VertexBinding
layout(set = 0, binding = ODESKIN_BINDING_SEGMENT_VERTICES) uniform usamplerBuffer segment_vertices; // SegmentVertex
layout(set = 0, binding = ODESKIN_BINDING_REMAINDERS) uniform samplerBuffer remainders;              // Float4
layout(set = 0, binding = ODESKIN_BINDING_INFLUENCE_OFFSETS) uniform usamplerBuffer influence_offsets; // uint
layout(set = 0, binding = ODESKIN_BINDING_INFLUENCES) uniform usamplerBuffer influences;             // Influence
layout(set = 0, binding = ODESKIN_BINDING_BONES) uniform samplerBuffer bones;                        // BoneMatrix: 3 texels
layout(set = 0, binding = ODESKIN_BINDING_MODE_BASIS) uniform samplerBuffer basis;                   // ModeBasis
layout(set = 0, binding = ODESKIN_BINDING_BONE_DUAL_QUATS) uniform samplerBuffer bone_dual_quats;    // DualQuat: 2 texels
layout(set = 0, binding = ODESKIN_BINDING_FOLDED_SERIES) uniform samplerBuffer folded_series;        // Float4

vec3 restPosition(uint i) { return texelFetch(rest_positions, int(i)).xyz; }

VertexBinding vertexBinding(uint i) {
  uvec4 t = texelFetch(bindings, int(i));
  return VertexBinding(t.x, t.y, uintBitsToFloat(t.z), uintBitsToFloat(t.w));
}

SegmentVertex segmentVertex(uint k) {
  uvec4 t = texelFetch(segment_vertices, int(k));
  return SegmentVertex(uintBitsToFloat(t.x), uintBitsToFloat(t.y), uintBitsToFloat(t.z), t.w);
}

vec3 remainder(uint k) { return texelFetch(remainders, int(k)).xyz; }
vec3 foldedCoefficient(uint k) { return texelFetch(folded_series, int(k)).xyz; }
uint influenceOffset(uint i) { return texelFetch(influence_offsets, int(i)).x; }

Influence influence(uint k) {
  uvec2 t = texelFetch(influences, int(k)).xy;
  return Influence(t.x, uintBitsToFloat(t.y));
}

// Row r (0..2) of bone b's 3x4 matrix.
vec4 boneRow(uint b, uint r) { return texelFetch(bones, int(3u * b + r)); }

ModeBasis modeBasis(uint k) {
  vec2 t = texelFetch(basis, int(k)).xy;
  return ModeBasis(t.x, t.y);
}

vec4 dualQuatReal(uint b) { return texelFetch(bone_dual_quats, int(2u * b)); }
vec4 dualQuatDual(uint b) { return texelFetch(bone_dual_quats, int(2u * b + 1u)); }
