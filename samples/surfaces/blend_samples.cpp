// SPDX-License-Identifier: MIT
// The blending samples that `odeskin blend` alone cannot make (thesis ch. 3), headless and
// self-checking:
//   OUT/corner.obj          the three-plane corner of Sec. 3.5: the top, front and side planes, the
//                           three rounded-edge blends of Eqs 3.22-3.24 and the three-sided patch of
//                           Eq 3.25 (MATH.md 2.13, C16, C17), one mesh
//   OUT/corner-patch.obj    the three-sided patch alone
//   OUT/corner-half.obj     corner.obj with the patch's bottom tangent scale s = -1/2 instead of -1
//   OUT/fig37-profiles.png  Fig. 3.7's profiles: the Eq 3.18 blend's cross-section at v = 0 for the
//                           cubic Hermite blend and the ODE blend with Fig. 3.7's three parameter sets
// Checks: every blend meets its four constraints, the blends and the patch share their corners,
// and the patch's side edges lie on the neighbouring blends' edges when s = -1/2; it prints how
// far they bulge apart with the default s = -1. Exit 0 when every check passes, 1 when one fails,
// 2 for a usage error.
// Usage: odeskin_blend_samples OUT_DIR [--res U,V]   (default 48,48 for each corner blend)
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine/io/obj_io.hpp"
#include "engine/surfaces/blend_examples.hpp"
#include "engine/surfaces/blending_surface.hpp"
#include "engine/surfaces/corner_blend.hpp"
#include "engine/surfaces/hermite_blend.hpp"
#include "engine/visual/compose.hpp"
#include "engine/visual/png_writer.hpp"
#include "engine/visual/text.hpp"
#include "samples/main_guard.hpp"

namespace {

using namespace odeskin;
namespace fs = std::filesystem;

constexpr double kConstraintLimit = 1e-12;

int failures = 0;

void check(bool ok, const std::string& what) {
  std::printf("%s %s\n", ok ? "ok:  " : "FAIL:", what.c_str());
  if (!ok) ++failures;
}

// Largest |S - C| and |S_u - Cbar| on both trimlines, relative to the data.
double constraintError(const BlendingSurface& s) {
  double error = 0.0, size = 0.0;
  for (int j = 0; j <= 32; ++j) {
    const double v = j / 32.0;
    const TrimlineSample b = s.boundary().at(v);
    size = std::max({size, glm::length(b.c0), glm::length(b.c1), glm::length(b.c0bar), glm::length(b.c1bar)});
    error = std::max({error, glm::length(s.at(0, v) - b.c0), glm::length(s.at(1, v) - b.c1),
                      glm::length(s.derivativeU(0, v) - b.c0bar), glm::length(s.derivativeU(1, v) - b.c1bar)});
  }
  return error / size;
}

void append(std::vector<Vec3>& positions, FaceList& faces, const std::vector<Vec3>& p, const FaceList& f) {
  const auto base = static_cast<std::uint32_t>(positions.size());
  positions.insert(positions.end(), p.begin(), p.end());
  for (std::size_t k = 0; k < f.faceCount(); ++k) {
    for (std::uint32_t i = f.face_offsets[k]; i < f.face_offsets[k + 1]; ++i) faces.indices.push_back(base + f.indices[i]);
    faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
  }
}

// Largest distance between the patch's v = 0 / v = 1 columns and TF's v = 1 / TS's v = 0 edges.
double sideEdgeGap(const CornerBlend& c) {
  double gap = 0.0;
  for (int i = 0; i <= 100; ++i) {
    const double u = i / 100.0;
    gap = std::max({gap, glm::length(c.patch.at(u, 0.0) - c.top_front.at(u, 1.0)),
                    glm::length(c.patch.at(u, 1.0) - c.top_side.at(u, 0.0))});
  }
  return gap;
}

// The planes, the three blends and the patch as one OBJ, and the patch alone.
Status writeCorner(const CornerBlend& c, const fs::path& path, const fs::path& patch_path, std::uint32_t u_count,
                   std::uint32_t v_count, const std::string& comment) {
  std::vector<Vec3> positions;
  FaceList faces;
  for (const auto& quad : cornerPlaneQuads(CornerDimensions{})) {
    FaceList f;
    f.indices = {0, 1, 2, 3};
    f.face_offsets = {0, 4};
    append(positions, faces, {quad.begin(), quad.end()}, f);
  }
  for (const BlendingSurface* part : {&c.top_front, &c.top_side, &c.front_side, &c.patch}) {
    ODESKIN_ASSIGN_OR_RETURN(const BlendGrid grid, tessellateBlend(*part, u_count, v_count));
    append(positions, faces, grid.positions, grid.faces);
    if (part == &c.patch && !patch_path.empty()) {
      ODESKIN_TRY(writeObj(patch_path, grid.positions, grid.faces, "thesis Eq 3.25 three-sided patch"));
    }
  }
  ODESKIN_TRY(writeObj(path, positions, faces, comment));
  std::printf("wrote %s (%zu vertices, %zu faces)\n", path.string().c_str(), positions.size(), faces.faceCount());
  return okStatus();
}

int corner(const fs::path& dir, std::uint32_t u_count, std::uint32_t v_count) {
  CornerBlendOptions half_options;
  half_options.bottom_tangent_scale = -0.5;
  Result<CornerBlend> blend = makeCornerBlend();
  Result<CornerBlend> half = makeCornerBlend(half_options);
  if (!blend.ok() || !half.ok()) {
    std::fprintf(stderr, "odeskin_blend_samples: corner blend: %s\n",
                 (blend.ok() ? half.status() : blend.status()).message().c_str());
    return 1;
  }
  const CornerBlend& c = *blend;
  const char* names[] = {"top-front (Eq 3.22)", "top-side (Eq 3.23, C16)", "front-side (Eq 3.24)", "three-sided patch (Eq 3.25)"};
  const BlendingSurface* parts[] = {&c.top_front, &c.top_side, &c.front_side, &c.patch};
  for (int k = 0; k < 4; ++k) {
    const double e = constraintError(*parts[k]);
    char line[160];
    std::snprintf(line, sizeof line, "%s meets its four constraints (%.1e of the data, limit %.0e)", names[k], e,
                  kConstraintLimit);
    check(e <= kConstraintLimit, line);
  }
  check(glm::length(c.top_front.at(0, 1) - c.top_side.at(0, 0)) < 1e-15, "S_TF(0, 1) = S_TS(0, 0), the corner of C16");
  check(glm::length(c.patch.at(1, 0) - c.top_front.at(1, 1)) < 1e-14 &&
            glm::length(c.patch.at(1, 1) - c.top_side.at(1, 0)) < 1e-14,
        "the patch's bottom corners are TF's and TS's lower corners");
  const double gap_default = sideEdgeGap(c);
  const double gap_half = sideEdgeGap(*half);
  char line[200];
  std::snprintf(line, sizeof line, "with s = -1/2 the patch's side edges lie on TF's and TS's edges (gap %.1e)", gap_half);
  check(gap_half < 1e-12, line);
  std::printf("note: with the default s = -1 (C17) the side edges bulge up to %.3f away (r = 0.25)\n", gap_default);
  for (const Status& s :
       {writeCorner(c, dir / "corner.obj", dir / "corner-patch.obj", u_count, v_count,
                    "thesis Sec. 3.5 corner: planes, Eqs 3.22-3.24 blends, Eq 3.25 patch with s = -1"),
        writeCorner(*half, dir / "corner-half.obj", {}, u_count, v_count,
                    "thesis Sec. 3.5 corner: planes, Eqs 3.22-3.24 blends, Eq 3.25 patch with s = -1/2")}) {
    if (!s.ok()) {
      std::fprintf(stderr, "odeskin_blend_samples: %s\n", s.message().c_str());
      return 1;
    }
  }
  return 0;
}

// Fig. 3.7: the Eq 3.18 blend's profile (x, z at v = 0) for Hermite and three ODE parameter sets.
int profiles(const fs::path& dir) {
  using visual::Rgba8;
  Result<BlendExample> e = blendExample("3.18");
  if (!e.ok()) return 1;
  struct Curve {
    std::string label;
    Rgba8 colour;
    std::vector<Vec3> points;
  };
  std::vector<Curve> curves;
  auto sample = [&](const BlendingSurface& s) {
    std::vector<Vec3> p;
    for (int i = 0; i <= 400; ++i) p.push_back(s.at(i / 400.0, 0.0));
    return p;
  };
  curves.push_back({"cubic Hermite (Eq 3.19)", {40, 40, 40, 255}, sample(*BlendingSurface::create(e->boundary, hermiteCardinals))});
  const Rgba8 colours[] = {{40, 170, 60, 255}, {230, 80, 170, 255}, {50, 100, 230, 255}};
  std::size_t k = 0;
  for (const LabelledParameters& p : figure37Parameters()) {
    Result<BlendingSurface> s = BlendingSurface::create(e->boundary, p.parameters.alpha, p.parameters.beta, p.parameters.gamma);
    if (!s.ok()) return 1;
    char label[96];
    std::snprintf(label, sizeof label, "ODE %g, %g, %g (%s)", p.parameters.alpha, p.parameters.beta, p.parameters.gamma,
                  p.label.c_str());
    curves.push_back({label, colours[k++], sample(*s)});
    double deviation = 0.0;
    for (std::size_t i = 0; i < curves.back().points.size(); ++i) {
      deviation = std::max(deviation, glm::length(curves.back().points[i] - curves.front().points[i]));
    }
    std::printf("profile %s: max distance from the Hermite profile %.4f\n", label, deviation);
  }
  // x horizontal, z up, each axis stretched to the plot so the differences between profiles show.
  double x0 = 1e9, x1 = -1e9, z0 = 1e9, z1 = -1e9;
  for (const Curve& c : curves) {
    for (const Vec3& p : c.points) {
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), z0 = std::min(z0, p.z), z1 = std::max(z1, p.z);
    }
  }
  const int width = 512, height = 384, left = 48, right = 16, top = 80, bottom = 36;
  const double sx = (width - left - right) / (x1 - x0), sz = (height - top - bottom) / (z1 - z0);
  visual::Image image(width, height, Rgba8{247, 247, 249, 255});
  const Rgba8 ink{60, 60, 60, 255};
  visual::fillRect(image, left, top, 1, height - top - bottom + 1, ink);
  visual::fillRect(image, left, height - bottom, width - left - right + 1, 1, ink);
  auto pixel = [&](const Vec3& p) {
    return std::pair<std::int64_t, std::int64_t>{static_cast<std::int64_t>(std::lround(left + (p.x - x0) * sx)),
                                                 static_cast<std::int64_t>(std::lround(top + (z1 - p.z) * sz))};
  };
  // The ODE profiles first, thick; the Hermite profile last and thin, so it stays visible.
  for (std::size_t n = 1; n <= curves.size(); ++n) {
    const Curve& c = curves[n % curves.size()];
    const int dot = n == curves.size() ? 1 : 3;
    for (std::size_t i = 0; i + 1 < c.points.size(); ++i) {
      for (int s = 0; s < 8; ++s) {  // dense dots along each chord
        const auto [x, y] = pixel(c.points[i] + (c.points[i + 1] - c.points[i]) * (s / 8.0));
        visual::fillRect(image, x - dot / 2, y - dot / 2, dot, dot, c.colour);
      }
    }
  }
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const auto y = static_cast<std::int64_t>(10 + 16 * i);
    visual::fillRect(image, 12, y, 18, 6, curves[i].colour);
    visual::drawText(image, 38, y - 1, curves[i].label, Rgba8{30, 30, 30, 255}, 1);
  }
  char tick[32];
  auto clean = [](double x) { return std::fabs(x) < 5e-3 ? 0.0 : x; };  // no "-0.00"
  std::snprintf(tick, sizeof tick, "z = %.2f", clean(z1));
  visual::drawText(image, 4, top - 12, tick, ink, 1);
  std::snprintf(tick, sizeof tick, "z = %.2f", clean(z0));
  visual::drawText(image, 4, height - bottom - 12, tick, ink, 1);
  std::snprintf(tick, sizeof tick, "x = %.2f", x0);
  visual::drawText(image, left, height - bottom + 6, tick, ink, 1);
  std::snprintf(tick, sizeof tick, "x = %.2f", x1);
  visual::drawText(image, width - right - 50, height - bottom + 6, tick, ink, 1);
  visual::drawText(image, left + 120, height - 14, "Eq 3.18 profile S(u, 0): x across, z up", Rgba8{90, 90, 90, 255}, 1);
  if (Status s = visual::writePng(dir / "fig37-profiles.png", image); !s.ok()) {
    std::fprintf(stderr, "odeskin_blend_samples: %s\n", s.message().c_str());
    return 1;
  }
  std::printf("wrote %s\n", (dir / "fig37-profiles.png").string().c_str());
  return 0;
}

bool parseRes(const std::string& text, std::uint32_t& u, std::uint32_t& v) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos) return false;
  auto a = std::from_chars(text.data(), text.data() + comma, u);
  auto b = std::from_chars(text.data() + comma + 1, text.data() + text.size(), v);
  return a.ec == std::errc() && a.ptr == text.data() + comma && b.ec == std::errc() &&
         b.ptr == text.data() + text.size() && u >= 2 && v >= 2 && u <= 2000 && v <= 2000;
}

}  // namespace

static int run(int argc, char** argv) {
  std::uint32_t u_count = 48, v_count = 48;
  std::string out_dir;
  std::string res;
  CLI::App app("odeskin_blend_samples: the thesis's three-plane corner (Eqs 3.22-3.25) and Fig. 3.7's "
               "profiles, self-checked");
  app.add_option("out_dir", out_dir, "Folder for the OBJ files and the profile plot")->required();
  app.add_option("--res", res, "Grid samples U,V of each blend, 2 to 2000 (default 48,48)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help exits 0; usage errors 2, as before
  }
  if (!res.empty() && !parseRes(res, u_count, v_count)) {
    std::fprintf(stderr, "odeskin_blend_samples: --res must be U,V with 2 <= U, V <= 2000, got '%s'\n", res.c_str());
    return 2;
  }
  const fs::path dir = out_dir;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    std::fprintf(stderr, "odeskin_blend_samples: %s: cannot create directory: %s\n", dir.string().c_str(), ec.message().c_str());
    return 1;
  }
  if (corner(dir, u_count, v_count) != 0 || profiles(dir) != 0) return 1;
  if (failures > 0) {
    std::fprintf(stderr, "odeskin_blend_samples: %d check(s) failed\n", failures);
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) { return odeskin::runGuarded("odeskin_blend_samples", run, argc, argv); }
