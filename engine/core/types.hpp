// SPDX-License-Identifier: MIT
// Plain value types shared by the CPU kernels and the offline code (double precision: the truth).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace odeskin {

using Vec2 = glm::dvec2;
using Vec3 = glm::dvec3;

// Affine bind-space -> posed-space bone transform: 3 rows x 4 columns, column-major like all of
// GLM; apply as `bone * glm::dvec4(x, 1.0)`.
using BoneTransform = glm::dmat4x3;

// Iso-parametric curve binding of one vertex (PIPELINE.md 3): the vertex evaluates
// (1 - w) series_{curve_a}(v) + w series_{curve_b}(v), w in [0, 1], v in [0, 1).
struct CurveBinding {
  std::uint32_t curve_a = 0;
  std::uint32_t curve_b = 0;
  double w = 0.0;
  double v = 0.0;
};

// Time basis values of one (material, mode) pair for the current frame: a_n = gamma d_n + psi rate_n.
struct ModeBasisValue {
  double gamma = 0.0;
  double psi = 0.0;
};

// Where the analytic residual lives (PIPELINE.md 3 and 6).
enum class ResidualSpace {
  kBind,   // added to the rest position before skinning, so it turns with the bones (default)
  kPosed,  // the thesis's variant: added after skinning
};

// How bones deform the (bind-space corrected) rest position: linear blend skinning, or
// dual-quaternion skinning (Kavan et al. 2008), which blends rigid transforms and keeps volume.
enum class SkinningMode : std::uint32_t {
  kLinear = 0,
  kDualQuaternion = 1,
};

// Polygon faces as compressed rows: face f has vertex indices [face_offsets[f], face_offsets[f+1]).
struct FaceList {
  std::vector<std::uint32_t> face_offsets{0};
  std::vector<std::uint32_t> indices;  // 0-based
  std::size_t faceCount() const { return face_offsets.size() - 1; }
};

// One glTF primitive of the input: a run of RenderLayout::faces and the material it was drawn with.
struct RenderPrimitive {
  std::uint32_t face_end = 0;  // its faces are [the previous primitive's face_end, face_end)
  std::int32_t material = -1;  // the input's material index, or -1 for none
  bool operator==(const RenderPrimitive&) const = default;
};

// glTF meshes are split at UV/normal seams: analysis runs on welded topology vertices, output keeps
// the input's render vertices. Empty `topology_of_render`: render layout == topology layout.
struct RenderLayout {
  std::vector<std::uint32_t> topology_of_render;  // render vertex -> topology vertex
  FaceList faces;                                 // faces over render vertices
  // The input's bind normals per render vertex (a glTF's NORMAL), or empty: they tell hard edges
  // from UV seams (smoothing_groups.hpp), so outputs keep the input's creases.
  std::vector<Vec3> normals;
  // The input's TEXCOORD_0 per render vertex, or empty: carried to the glTF the exports write, so
  // the character keeps its texture mapping.
  std::vector<Vec2> uvs;
  // The input's primitives in file order, or empty for one primitive without a material: the
  // exports write them back as they were, so `export --materials` can give each its material.
  std::vector<RenderPrimitive> primitives;
  // The layout came from an OBJ's `vt`/`vn` corners (objRenderLayout). OBJ frames and point caches
  // then keep the topology vertices in the input's order, each corner naming its `vt`, so a point
  // cache still fits the mesh the user started from; glTF outputs use the render vertices.
  bool obj_order = false;
  bool empty() const { return topology_of_render.empty(); }
};

}  // namespace odeskin
