// SPDX-License-Identifier: MIT
// The thesis's blending examples (ch. 3, Eqs 3.15-3.18) as boundary data, read as MATH.md 2.13
// specifies. Eq 3.14 is garbled beyond repair (MATH.md C14) and is not provided.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "../core/result.hpp"
#include "boundary_data.hpp"

namespace odeskin {

struct BlendShapeParameters {
  double alpha = 1.0;
  double beta = 0.0;
  double gamma = 0.0;
};

struct BlendExample {
  std::string id;                  // "3.15"
  std::string description;         // one line: what is blended, and any reading of garbled data
  BoundaryData boundary;           // v in [0, 2 pi), periodic
  BlendShapeParameters thesis;     // the shape parameters the thesis uses with it
};

// "3.15", "3.16", "3.17", "3.18".
std::vector<std::string> blendExampleIds();

// Eq 3.15: torus iso-line at 0.85 (taken with trimlineFromSurface) to an ellipse, (1, 2, 1);
//   the u = 1 data lost a parameter value and a coefficient (C15): literal reading with 0 and
//   y-coefficient 1.05.
// Eq 3.16: a 12-lobed curve to a circle, (1, 3, 1).
// Eq 3.17: a circle to a hyperboloid's iso-line at 1.4, (1, 1, 1).
// Eq 3.18: a 7-lobed curve to an ellipse (Figs 3.5-3.7); its thesis parameters here are Fig
//   3.5(a)'s (1, 0.5, 1).
// Errors: kInvalidArgument for "3.14" (garbled, C14) and for any other unknown id, listing the
// valid ones.
Result<BlendExample> blendExample(std::string_view id);

// Shape parameters of the thesis's studies on Eq 3.18 (labels as the thesis's figure panels).
struct LabelledParameters {
  std::string label;
  BlendShapeParameters parameters;
};
std::vector<LabelledParameters> figure35Parameters();  // Fig 3.5 (a)-(d)
std::vector<LabelledParameters> figure37Parameters();  // Fig 3.7 green, pink, blue profiles

}  // namespace odeskin
