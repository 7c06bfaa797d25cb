// SPDX-License-Identifier: MIT
#include "rig_picture.hpp"

#include <algorithm>
#include <tuple>

#include "engine/visual/curve_lines.hpp"
#include "engine/visual/png_writer.hpp"
#include "render_session.hpp"

namespace odeskin {
namespace {

// Palette entries (visual::curveColour): blue for the x-ray curves, green for the curve
// skeleton, red for the bones and joints.
constexpr std::uint32_t kCurveColour = 0;
constexpr std::uint32_t kCentroidColour = 2;
constexpr std::uint32_t kBoneColour = 3;
constexpr std::uint32_t kTruthColour = 4;

void addSegment(PanelGeometry& g, const Vec3& a, const Vec3& b, std::uint32_t colour) {
  g.curve_endpoints.push_back(a);
  g.curve_endpoints.push_back(b);
  g.curve_ids.push_back(colour);
}

}  // namespace

Status drawRigPicture(const std::filesystem::path& path, std::span<const Vec3> positions, const FaceList& faces,
                      std::span<const IsoCurve> curves, const CurveSkeleton& cs, const AnimationSkeleton& skeleton,
                      const RigPictureOptions& o) {
  const std::vector<IsoCurve> curve_list(curves.begin(), curves.end());
  ODESKIN_ASSIGN_OR_RETURN(PanelGeometry surface,
                           preparePanel(path.string(), std::vector<Vec3>(positions.begin(), positions.end()), faces, &curve_list));
  surface.label = {o.title, "iso-parametric curves by body part"};

  PanelGeometry xray;
  xray.positions.assign(positions.begin(), positions.end());
  xray.normals.assign(positions.size(), Vec3(0.0, 0.0, 1.0));
  ODESKIN_ASSIGN_OR_RETURN(visual::CurveSegments segments, visual::curveSegments(curves, positions));
  xray.curve_endpoints = std::move(segments.endpoints);
  xray.curve_ids.assign(xray.curve_endpoints.size() / 2, kCurveColour);
  for (std::size_t n = 1; n < cs.nodeCount(); ++n) {
    addSegment(xray, cs.positions[static_cast<std::size_t>(cs.parents[n])], cs.positions[n], kCentroidColour);
  }
  Vec3 lo(1e300), hi(-1e300);
  for (const Vec3& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const double cross = 0.012 * glm::length(hi - lo);  // joint markers: small 3-axis crosses
  for (std::size_t j = 0; j < skeleton.jointCount(); ++j) {
    const Vec3& p = skeleton.joints[j];
    if (skeleton.parents[j] >= 0) addSegment(xray, skeleton.joints[static_cast<std::size_t>(skeleton.parents[j])], p, kBoneColour);
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 d(0.0);
      d[axis] = cross;
      addSegment(xray, p - d, p + d, kBoneColour);
    }
  }
  if (o.truth != nullptr) {
    for (std::size_t b = 0; b < o.truth->boneCount(); ++b) addSegment(xray, o.truth->heads[b], o.truth->tails[b], kTruthColour);
  }
  xray.label = {std::to_string(skeleton.boneCount()) + " bones (red), curve skeleton (green)" +
                    (o.truth != nullptr ? ", truth (purple)" : ""),
                std::string("template: ") + std::string(templateKindName(skeleton.used))};

  visual::PictureSpec spec;
  std::tie(spec.width, spec.height) = *parseImageSize(o.size);
  spec.panels = 2;
  spec.label_lines = 2;
  ODESKIN_ASSIGN_OR_RETURN(visual::PictureLayout layout, visual::layoutPicture(spec));
  visual::ViewSpec view;
  view.up = o.up;
  view.azimuth_deg = o.azimuth_deg;
  view.elevation_deg = o.elevation_deg;
  ODESKIN_ASSIGN_OR_RETURN(visual::Camera camera,
                           visual::framePoints(positions, double(layout.panel_width) / double(layout.panel_height), view));
  ODESKIN_ASSIGN_OR_RETURN(RenderSession session, RenderSession::open(o.device, false, vk::PictureStyle{}));
  const std::vector<vk::PanelContent> contents{surface.content(), xray.content()};
  ODESKIN_ASSIGN_OR_RETURN(visual::Image picture, session.draw(layout, camera, glm::length(hi - lo), contents));
  return visual::writePng(path, picture);
}

}  // namespace odeskin
