// SPDX-License-Identifier: MIT
#include "blend_examples.hpp"

#include <cmath>

namespace odeskin {
namespace {

Result<BlendExample> assemble(std::string id, std::string description, Result<Trimline> start, Result<Trimline> end,
                              BlendShapeParameters thesis) {
  if (!start.ok()) return start.status();
  if (!end.ok()) return end.status();
  ODESKIN_ASSIGN_OR_RETURN(BoundaryData boundary, BoundaryData::create(std::move(*start), std::move(*end)));
  return BlendExample{std::move(id), std::move(description), std::move(boundary), thesis};
}

Result<BlendExample> example315() {
  // The u = 0 trimline is the torus ((1.7 + 0.45 cos s) cos v, (1.7 + 0.45 cos s) sin v, 0.45 sin s)
  // at s = 0.85; the printed C0bar is -(2.45/0.45) dP/ds there.
  SurfaceFunction torus = [](double s, double v) {
    const double ring = 1.7 + 0.45 * std::cos(s);
    return Vec3(ring * std::cos(v), ring * std::sin(v), 0.45 * std::sin(s));
  };
  SurfaceFunction torus_ds = [](double s, double v) {
    return Vec3(-0.45 * std::sin(s) * std::cos(v), -0.45 * std::sin(s) * std::sin(v), 0.45 * std::cos(s));
  };
  return assemble("3.15",
                  "torus iso-line to an ellipse, (1, 2, 1); u = 1 data read literally with the lost parameter 0 "
                  "and y-coefficient 1.05 (MATH.md C15)",
                  trimlineFromSurface(torus, torus_ds, 0.85, -2.45 / 0.45),
                  trimlineFromFunctions([](double v) { return Vec3(1.5 * std::cos(v), 1.05 * std::sin(v), 0.0); },
                                        [](double v) { return Vec3(std::cos(v), 0.7 * std::sin(v), -1.5); }),
                  {1.0, 2.0, 1.0});
}

Result<BlendExample> example316() {
  auto lobes = [](double v) {
    return Vec3(0.909 * std::cos(v) + 0.051 * std::cos(12.0 * v), 0.909 * std::sin(v) + 0.051 * std::sin(12.0 * v), 0.0);
  };
  return assemble("3.16", "12-lobed curve to a circle, (1, 3, 1)",
                  trimlineFromFunctions([lobes](double v) { return 1.013 * lobes(v) + Vec3(0.0, 0.0, 0.95); },
                                        [lobes](double v) { return 0.26 * lobes(v) + Vec3(0.0, 0.0, -2.1); }),
                  trimlineFromFunctions([](double v) { return Vec3(1.3 * std::cos(v), 1.3 * std::sin(v), -1.2); },
                                        [](double v) { return Vec3(-0.5 * std::cos(v), -0.5 * std::sin(v), -2.0); }),
                  {1.0, 3.0, 1.0});
}

Result<BlendExample> example317() {
  const double sh = std::sinh(1.4);
  const double ch = std::cosh(1.4);
  return assemble(
      "3.17", "circle to a hyperboloid iso-line at 1.4, (1, 1, 1)",
      trimlineFromFunctions([](double v) { return Vec3(0.9 * std::cos(v), 0.9 * std::sin(v), 0.4); },
                            [](double) { return Vec3(0.0, 0.0, -1.8); }),
      trimlineFromFunctions([sh, ch](double v) { return Vec3(0.6 * sh * std::cos(v), 0.4 * sh * std::sin(v), -1.5 * ch); },
                            [sh, ch](double v) { return Vec3(0.6 * ch * std::cos(v), 0.4 * ch * std::sin(v), -1.35 * sh); }),
      {1.0, 1.0, 1.0});
}

Result<BlendExample> example318() {
  auto lobes = [](double v) {
    return Vec3(0.9 * std::cos(v) + 0.1 * std::cos(7.0 * v), 0.9 * std::sin(v) + 0.1 * std::sin(7.0 * v), 0.0);
  };
  return assemble("3.18", "7-lobed curve to an ellipse, the shape study of Figs 3.5-3.7; default (1, 0.5, 1) of Fig 3.5(a)",
                  trimlineFromFunctions([lobes](double v) { return 1.015 * lobes(v) + Vec3(0.0, 0.0, 1.65); },
                                        [lobes](double v) { return 0.02 * lobes(v) + Vec3(0.0, 0.0, -0.1); }),
                  trimlineFromFunctions([](double v) { return Vec3(1.6 * std::cos(v), 1.2 * std::sin(v), 0.0); },
                                        [](double v) { return Vec3(1.2 * std::cos(v), 1.2 * std::sin(v), -1.8); }),
                  {1.0, 0.5, 1.0});
}

}  // namespace

std::vector<std::string> blendExampleIds() { return {"3.15", "3.16", "3.17", "3.18"}; }

Result<BlendExample> blendExample(std::string_view id) {
  if (id == "3.15") return example315();
  if (id == "3.16") return example316();
  if (id == "3.17") return example317();
  if (id == "3.18") return example318();
  if (id == "3.14") {
    return invalidArgument("blend example 3.14 is garbled in the thesis (its trimline is not a closed curve of v, "
                           "MATH.md C14); use 3.15, 3.16, 3.17 or 3.18");
  }
  return invalidArgument("unknown blend example '" + std::string(id) + "' (expected 3.15, 3.16, 3.17 or 3.18)");
}

std::vector<LabelledParameters> figure35Parameters() {
  return {{"Fig 3.5(a)", {1.0, 0.5, 1.0}},
          {"Fig 3.5(b)", {3.7, 2.5, 1.0}},
          {"Fig 3.5(c)", {3.7, 2.0, 18.0}},
          {"Fig 3.5(d)", {2.0, 0.5, 1.0}}};
}

std::vector<LabelledParameters> figure37Parameters() {
  return {{"Fig 3.7 green", {1.0, 1.0, 0.1}}, {"Fig 3.7 pink", {1.0, 11.0, 1.0}}, {"Fig 3.7 blue", {1.0, 17.0, 1.0}}};
}

}  // namespace odeskin
