// SPDX-License-Identifier: MIT
#include "corner_blend.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace odeskin {
namespace {

Status checkDimensions(const CornerDimensions& d) {
  const std::pair<const char*, double> all[] = {{"y0", d.y0}, {"z0", d.z0}, {"lx", d.lx},
                                                 {"ly", d.ly}, {"lz", d.lz}, {"r", d.r}};
  for (const auto& [name, value] : all) {
    if (!std::isfinite(value)) return invalidArgument(std::string("corner blend: ") + name + " is not finite");
  }
  const std::pair<const char*, double> lengths[] = {{"lx", d.lx}, {"ly", d.ly}, {"lz", d.lz}, {"r", d.r}};
  for (const auto& [name, value] : lengths) {
    if (!(value > 0.0)) return invalidArgument(std::string("corner blend: ") + name + " must be positive");
  }
  return okStatus();
}

Result<BlendingSurface> planeBlend(CurveFunction c0, CurveFunction c0bar, CurveFunction c1, CurveFunction c1bar,
                                   const BlendShapeParameters& p) {
  const VDomain unit{0.0, 1.0, false};
  ODESKIN_ASSIGN_OR_RETURN(Trimline start, trimlineFromFunctions(std::move(c0), std::move(c0bar)));
  ODESKIN_ASSIGN_OR_RETURN(Trimline end, trimlineFromFunctions(std::move(c1), std::move(c1bar)));
  ODESKIN_ASSIGN_OR_RETURN(BoundaryData boundary, BoundaryData::create(std::move(start), std::move(end), unit));
  return BlendingSurface::create(std::move(boundary), p.alpha, p.beta, p.gamma);
}

// l(v): arc length of `curve` from 0 to v over its total, from 2048 chords (piecewise linear in v;
// l only spreads the top tangent along the patch, so a smooth monotone reading is all it needs).
std::shared_ptr<const std::vector<double>> arcLengthTable(const CurveFunction& curve) {
  constexpr int kChords = 2048;
  auto table = std::make_shared<std::vector<double>>(kChords + 1, 0.0);
  Vec3 previous = curve(0.0);
  for (int i = 1; i <= kChords; ++i) {
    const Vec3 p = curve(static_cast<double>(i) / kChords);
    (*table)[static_cast<std::size_t>(i)] = (*table)[static_cast<std::size_t>(i - 1)] + glm::length(p - previous);
    previous = p;
  }
  const double total = table->back();
  for (double& x : *table) x /= total;
  return table;
}

double lookup(const std::vector<double>& table, double v) {
  const double x = std::clamp(v, 0.0, 1.0) * static_cast<double>(table.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), table.size() - 2);
  const double s = x - static_cast<double>(i);
  return (1.0 - s) * table[i] + s * table[i + 1];
}

}  // namespace

Result<CornerBlend> makeCornerBlend(const CornerBlendOptions& options) {
  const CornerDimensions d = options.dimensions;
  ODESKIN_TRY(checkDimensions(d));
  if (!std::isfinite(options.bottom_tangent_scale)) {
    return invalidArgument("corner blend: bottom_tangent_scale is not finite");
  }
  const BlendShapeParameters& p = options.parameters;
  const double top = d.z0 + d.lz + d.r;
  // Eq 3.22, top to front.
  ODESKIN_ASSIGN_OR_RETURN(
      BlendingSurface tf,
      planeBlend([=](double v) { return Vec3(d.lx * v, d.y0 + d.r, top); },
                 [=](double) { return Vec3(0.0, -0.5 * d.ly, 0.0); },
                 [=](double v) { return Vec3(d.lx * v, d.y0, d.z0 + d.lz); },
                 [=](double) { return Vec3(0.0, 0.0, -0.5 * d.lz); }, p));
  // Eq 3.23 with C16: the u = 0 trimline runs along y on the top plane at x = lx.
  ODESKIN_ASSIGN_OR_RETURN(
      BlendingSurface ts,
      planeBlend([=](double v) { return Vec3(d.lx, d.y0 + d.r + d.ly * v, top); },
                 [=](double) { return Vec3(0.5 * d.lx, 0.0, 0.0); },
                 [=](double v) { return Vec3(d.lx + d.r, d.y0 + d.r + d.ly * v, d.z0 + d.lz); },
                 [=](double) { return Vec3(0.0, 0.0, -0.5 * d.lz); }, p));
  // Eq 3.24, front to side.
  ODESKIN_ASSIGN_OR_RETURN(
      BlendingSurface fs,
      planeBlend([=](double v) { return Vec3(d.lx, d.y0, d.z0 + d.lz * v); },
                 [=](double) { return Vec3(0.5 * d.lx, 0.0, 0.0); },
                 [=](double v) { return Vec3(d.lx + d.r, d.y0 + d.r, d.z0 + d.lz * v); },
                 [=](double) { return Vec3(0.0, 0.5 * d.ly, 0.0); }, p));

  // Eq 3.25 with C17. FS's trimlines are linear in v with slope (0, 0, lz) and its tangents are
  // constant, so dS_FS/dv(u, v) = (r1(u) + r3(u)) (0, 0, lz) exactly.
  const Vec3 corner = tf.at(0.0, 1.0);
  const Vec3 t0 = tf.derivativeU(0.0, 1.0);
  const Vec3 t1 = ts.derivativeU(0.0, 0.0);
  CurveFunction bottom = [fs](double v) { return fs.at(v, 1.0); };
  auto l = arcLengthTable(bottom);
  const double scale = options.bottom_tangent_scale;
  const CardinalFunction fs_cardinals = fs.cardinals();
  ODESKIN_ASSIGN_OR_RETURN(
      BlendingSurface patch,
      planeBlend([corner](double) { return corner; },
                 [t0, t1, l](double v) { return t0 + (t1 - t0) * lookup(*l, v); }, bottom,
                 [fs_cardinals, scale, lz = d.lz](double v) {
                   const CardinalSample s = fs_cardinals(v);
                   return scale * (s.r[0] + s.r[2]) * Vec3(0.0, 0.0, lz);
                 },
                 p));
  return CornerBlend{std::move(tf), std::move(ts), std::move(fs), std::move(patch)};
}

std::array<std::array<Vec3, 4>, 3> cornerPlaneQuads(const CornerDimensions& d) {
  const double top = d.z0 + d.lz + d.r;
  const double y1 = d.y0 + d.r;
  const double y2 = y1 + d.ly;
  const double side = d.lx + d.r;
  return {{
      {Vec3(0.0, y1, top), Vec3(d.lx, y1, top), Vec3(d.lx, y2, top), Vec3(0.0, y2, top)},                  // +z
      {Vec3(0.0, d.y0, d.z0), Vec3(d.lx, d.y0, d.z0), Vec3(d.lx, d.y0, d.z0 + d.lz), Vec3(0.0, d.y0, d.z0 + d.lz)},  // -y
      {Vec3(side, y1, d.z0), Vec3(side, y2, d.z0), Vec3(side, y2, d.z0 + d.lz), Vec3(side, y1, d.z0 + d.lz)},  // +x
  }};
}

}  // namespace odeskin
