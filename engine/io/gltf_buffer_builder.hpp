// SPDX-License-Identifier: MIT
// Writing glTF data into one model's buffer 0 (internal to the glTF writers: the baked, rig,
// surface and export GLBs). Every view is 4-byte aligned, which glTF requires of vertex attributes
// and matrices, so views of any element type can follow each other in the one buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin::gltf {

// glTF stores positions as float32: a coordinate beyond float's range would be written as an
// infinity (and its accessor's min/max as null), and a mesh far below float's normal range as
// zeros. kInvalidArgument "<who>: vertex I is outside glTF's float32 range (|coordinate| up to
// 1e+38); scale the mesh down" (kFloat32CoordinateLimit, the packed deform data's bound too), or
// "<who>: the mesh spans S, too small for glTF's float32 positions (at least 1e-30); scale it up"
// for a longest box side in (0, 1e-30). Positions must be finite.
Status checkFloat32Positions(std::span<const Vec3> positions, const std::string& who);

// A glTF 2.0 model with one empty buffer, ready for appendView.
tinygltf::Model newModel(const std::string& generator);

// Appends `size` bytes to buffer 0 (which must exist) as a new view; target 0 leaves the view's
// target unset. Returns the view's index.
int appendView(tinygltf::Model& m, const void* bytes, std::size_t size, int target);

template <class T>
int appendView(tinygltf::Model& m, const std::vector<T>& values, int target) {
  return appendView(m, values.data(), values.size() * sizeof(T), target);
}

// An accessor over a whole view; returns its index.
int appendAccessor(tinygltf::Model& m, int view, int component_type, int type, std::size_t count);

// Per-component min/max of interleaved `values` (`components` per element); with_zero starts both
// at 0 (a sparse accessor's unsubstituted elements are zero).
void setBounds(tinygltf::Accessor& a, std::span<const float> values, int components, bool with_zero);

// A float accessor over a new view of `values`, with min/max per component when asked (POSITION
// and animation inputs need them). Returns the accessor's index.
int appendFloatAccessor(tinygltf::Model& m, const std::vector<float>& values, int type, int components, int target,
                        bool bounds);

// A float VEC2 TEXCOORD accessor over a new ARRAY_BUFFER view of `uvs`.
int appendTexcoordAccessor(tinygltf::Model& m, std::span<const Vec2> uvs);

// An UNSIGNED_INT index accessor over a new ELEMENT_ARRAY_BUFFER view of `triangles`.
int appendTriangleIndices(tinygltf::Model& m, const std::vector<std::uint32_t>& triangles);

// Node 0 showing mesh 0 under `name`, and scene 0 (the default) holding just that node.
void addSingleMeshScene(tinygltf::Model& m, const std::string& name);

// The polygons as triangle fans (v0, vk, vk+1), the way every odeskin GLB triangulates.
std::vector<std::uint32_t> fanTriangles(const FaceList& faces);
// The same of faces [first_face, end_face).
std::vector<std::uint32_t> fanTriangles(const FaceList& faces, std::size_t first_face, std::size_t end_face);

}  // namespace odeskin::gltf
