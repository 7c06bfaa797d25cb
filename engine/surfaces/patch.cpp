// SPDX-License-Identifier: MIT
#include "patch.hpp"

namespace odeskin {

Result<Patch> Patch::create(const Ode6Shape& shape, PatchCurves curves) {
  ODESKIN_ASSIGN_OR_RETURN(Ode6Cardinal cardinal, Ode6Cardinal::create(shape));
  return create(cardinal, std::move(curves));
}

Result<Patch> Patch::create(const Ode6Cardinal& cardinal, PatchCurves curves) {
  for (std::size_t k = 0; k < curves.size(); ++k) {
    if (!curves[k]) return invalidArgument("patch: boundary curve c" + std::to_string(k + 1) + " is empty");
  }
  return Patch(cardinal, std::move(curves));
}

Vec3 Patch::position(double u, double v) const {
  const Ode6Values g = cardinal_.evaluate(u);
  Vec3 s(0.0);
  for (std::size_t k = 0; k < 6; ++k) s += g[k] * curves_[k](v, 0);
  return s;
}

PatchPoint Patch::evaluate(double u, double v) const {
  std::array<Ode6Values, 3> g{};
  cardinal_.evaluate(u, g);
  PatchPoint p;
  for (std::size_t k = 0; k < 6; ++k) {
    const Vec3 c = curves_[k](v, 0);
    const Vec3 c_v = curves_[k](v, 1);
    const Vec3 c_vv = curves_[k](v, 2);
    p.s += g[0][k] * c;
    p.s_u += g[1][k] * c;
    p.s_uu += g[2][k] * c;
    p.s_v += g[0][k] * c_v;
    p.s_vv += g[0][k] * c_vv;
    p.s_uv += g[1][k] * c_v;
  }
  return p;
}

}  // namespace odeskin
