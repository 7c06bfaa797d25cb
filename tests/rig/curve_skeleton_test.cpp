// SPDX-License-Identifier: MIT
#include "engine/rig/curve_skeleton.hpp"

#include <cstdio>

#include <gtest/gtest.h>

#include "engine/io/obj_reader.hpp"

namespace odeskin {
namespace {

TEST(CurveSkeleton, Debug) {
  for (const char* name : {"cylinder/cylinder.obj", "cat-poses/cat-00.obj", "horse-gallop/horse-01.obj", "cheburashka/cheburashka.obj"}) {
    Result<ObjMesh> mesh = readObj(std::string(ODESKIN_DATA_DIR) + "/" + name);
    ASSERT_TRUE(mesh.ok()) << mesh.status().message();
    for (CurveSource src : {CurveSource::kLevels, CurveSource::kPlaneCuts}) {
      CurveSkeletonOptions o;
      o.source = src;
      Result<CurveSkeletonResult> r = buildCurveSkeleton(mesh->positions, mesh->faces, o);
      ASSERT_TRUE(r.ok()) << r.status().message();
      std::size_t j = 0, t = 0;
      for (auto k : r->skeleton.kinds) { j += k == SkeletonNodeKind::kJunction; t += k == SkeletonNodeKind::kTip; }
      std::printf("%s %s: nodes %zu junctions %zu tips %zu parts %zu pruned %zu curves %zu; %.3f ms + %.3f ms %s\n", name,
                  src == CurveSource::kLevels ? "levels" : "cuts", r->skeleton.nodeCount(), j, t, r->part_count,
                  r->pruned_branches, r->curves.size(), 1e3 * r->seconds_curves, 1e3 * r->seconds_skeleton, r->note.c_str());
    }
  }
}

}  // namespace
}  // namespace odeskin
