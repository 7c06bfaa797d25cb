// SPDX-License-Identifier: MIT
#include "blend_command.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

#include "engine/core/machine_memory.hpp"
#include "engine/core/number_text.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/surfaces/blend_examples.hpp"
#include "engine/surfaces/blending_surface.hpp"
#include "engine/surfaces/cardinal_spline.hpp"
#include "engine/surfaces/hermite_blend.hpp"
#include "file_extension.hpp"
#include "output_paths.hpp"

namespace odeskin {
namespace {

constexpr std::uint32_t kMaxSide = 100000;
constexpr int kMaxSplinePieces = 1000;
// The constraints hold to rounding (~1e-15 of the data); anything near this bound is a bug.
constexpr double kConstraintLimit = 1e-9;
// The thesis's examples stay within a few times their data; a hundred times is a bulge, not a blend.
constexpr double kFarReach = 100.0;

bool parseCount(std::string_view text, std::uint32_t& value) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end;
}

// "U,V" -> (U, V), or a usage message.
std::string parseResolution(const std::string& res, std::uint32_t& u, std::uint32_t& v) {
  const std::size_t comma = res.find(',');
  if (comma == std::string::npos || !parseCount(std::string_view(res).substr(0, comma), u) ||
      !parseCount(std::string_view(res).substr(comma + 1), v)) {
    return "blend: --res must be two positive integers U,V (e.g. 64,128), got '" + res + "'";
  }
  if (u < 2 || u > kMaxSide) return "blend: --res U = " + std::to_string(u) + " must be in [2, 100000]";
  if (v < 3 || v > kMaxSide) {
    return "blend: --res V = " + std::to_string(v) + " must be in [3, 100000] (the grid wraps in v)";
  }
  if (std::uint64_t{u} * v > kMaxBlendGridVertices) {
    return "blend: --res " + res + " gives more than " + std::to_string(kMaxBlendGridVertices) + " vertices";
  }
  return {};
}

std::string usageProblem(const BlendCommandOptions& o, std::uint32_t& u, std::uint32_t& v) {
  if (o.example.empty()) return "blend: --example is required (3.15, 3.16, 3.17 or 3.18)";
  if (o.example == "3.14") {
    return "blend: example 3.14 is garbled in the thesis and cannot be reconstructed (MATH.md C14); use 3.15, "
           "3.16, 3.17 or 3.18";
  }
  const std::vector<std::string> ids = blendExampleIds();
  if (std::find(ids.begin(), ids.end(), o.example) == ids.end()) {
    return "blend: unknown example '" + o.example + "' (expected 3.15, 3.16, 3.17 or 3.18)";
  }
  for (const auto& [name, value] : {std::pair{"--alpha", o.alpha}, std::pair{"--beta", o.beta}, std::pair{"--gamma", o.gamma}}) {
    if (value && !std::isfinite(*value)) return std::string("blend: ") + name + " must be a finite number, got " + numberText(*value);
  }
  if (o.hermite && (o.alpha || o.beta || o.gamma)) {
    return "blend: --hermite is the cubic Hermite blend and takes no --alpha, --beta or --gamma";
  }
  if (o.hermite && o.spline_pieces) return "blend: --hermite and --spline exclude each other";
  if (o.spline_pieces && (*o.spline_pieces < 1 || *o.spline_pieces > kMaxSplinePieces)) {
    return "blend: --spline must be in [1, 1000] pieces, got " + std::to_string(*o.spline_pieces);
  }
  if (std::string problem = parseResolution(o.res, u, v); !problem.empty()) return problem;
  if (o.output.empty()) return "blend: -o OUT.obj is required";
  const std::string ext = lowerExtension(o.output);
  if (ext != ".obj") return "blend: " + o.output.string() + ": unknown output format '" + ext + "' (expected .obj)";
  return {};
}

// Largest deviation from the four constraints over the grid's v samples (relative to the data).
void checkConstraints(const BlendingSurface& s, const BlendGrid& g, BlendReport& r) {
  double size = 0.0, tangent_size = 0.0, position = 0.0, tangent = 0.0;
  for (std::uint32_t j = 0; j < g.v_count; ++j) {
    const double v = blendGridV(s.boundary().domain(), g.v_count, j);
    const TrimlineSample b = s.boundary().at(v);
    size = std::max({size, glm::length(b.c0), glm::length(b.c1)});
    tangent_size = std::max({tangent_size, glm::length(b.c0bar), glm::length(b.c1bar)});
    position = std::max({position, glm::length(g.positions[j] - b.c0),
                         glm::length(g.positions[std::size_t{g.u_count - 1} * g.v_count + j] - b.c1)});
    tangent = std::max({tangent, glm::length(s.derivativeU(0.0, v) - b.c0bar), glm::length(s.derivativeU(1.0, v) - b.c1bar)});
  }
  r.position_error = position / std::max(size, 1e-300);
  r.tangent_error = tangent / std::max(tangent_size + size, 1e-300);
  double reach = 0.0;
  for (const Vec3& p : g.positions) reach = std::max(reach, glm::length(p));
  r.reach = reach / std::max(tangent_size + size, 1e-300);
}

Status withVerb(const Status& s) { return Status(s.code(), "blend: " + s.message()); }

}  // namespace

Status blendFitsInMemory(std::uint64_t vertices, std::uint64_t memory_bytes) {
  // vertices <= kMaxBlendGridVertices (5e7), so the product stays far from overflow.
  return checkFitsInMemory(vertices * kBlendBytesPerVertex, memory_bytes,
                           "blend: " + std::to_string(vertices) + " grid vertices", "lower --res");
}

int runBlendCommand(const BlendCommandOptions& o, Console& console, BlendReport* report) {
  std::uint32_t u_count = 0, v_count = 0;
  if (const std::string problem = usageProblem(o, u_count, v_count); !problem.empty()) return reportUsage(console, problem);
  if (Status fits = blendFitsInMemory(std::uint64_t{u_count} * v_count, physicalMemoryBytes()); !fits.ok()) {
    return reportFailure(console, fits);
  }
  Result<BlendExample> example = blendExample(o.example);
  if (!example.ok()) return reportFailure(console, withVerb(example.status()));

  BlendReport r;
  r.u_count = u_count;
  r.v_count = v_count;
  r.alpha = o.alpha.value_or(example->thesis.alpha);
  r.beta = o.beta.value_or(example->thesis.beta);
  r.gamma = o.gamma.value_or(example->thesis.gamma);
  CardinalFunction cardinals = hermiteCardinals;
  std::string profile = "cubic Hermite (Eq 3.19)";
  if (!o.hermite) {
    Result<Ode4Cardinal> cardinal = Ode4Cardinal::create(r.alpha, r.beta, r.gamma);
    if (!cardinal.ok()) return reportFailure(console, withVerb(cardinal.status()));
    r.regime = ode4RegimeName(cardinal->regime());
    profile = "ODE alpha " + numberText(r.alpha) + ", beta " + numberText(r.beta) + ", gamma " + numberText(r.gamma);
    cardinals = [c = *cardinal](double u) { return c.at(u); };
    if (o.spline_pieces) {
      Result<CardinalSpline> spline = CardinalSpline::fit(*cardinal, *o.spline_pieces);
      if (!spline.ok()) return reportFailure(console, withVerb(spline.status()));
      cardinals = [s = *spline](double u) { return s.at(u); };
      profile += ", clamped cubic spline with " + std::to_string(*o.spline_pieces) + " pieces";
    }
  }
  Result<BlendingSurface> surface = BlendingSurface::create(example->boundary, std::move(cardinals));
  if (!surface.ok()) return reportFailure(console, withVerb(surface.status()));
  Result<BlendGrid> grid = tessellateBlend(*surface, u_count, v_count);
  if (!grid.ok()) return reportFailure(console, withVerb(grid.status()));
  checkConstraints(*surface, *grid, r);
  if (!(r.position_error <= kConstraintLimit) || !(r.tangent_error <= kConstraintLimit)) {
    return reportFailure(console, internalError("blend: the surface misses its trimline constraints by " +
                                                scientific(std::max(r.position_error, r.tangent_error))));
  }

  if (Status s = createParentFolder(o.output); !s.ok()) return reportFailure(console, Status(s.code(), "blend: " + s.message()));
  const std::string comment = "odeskin blend --example " + o.example + ": " + profile + "; grid " +
                              std::to_string(u_count) + " x " + std::to_string(v_count) +
                              ", vertex i*V+j = S(i/(U-1), 2 pi j/V)";
  if (Status s = writeObj(o.output, grid->positions, grid->faces, comment); !s.ok()) {
    return reportFailure(console, withVerb(s));
  }
  if (!console.quiet) {
    console.out << "blend " << o.example << " (" << example->description << ")\n";
    console.out << "profile: " << profile;
    if (!r.regime.empty()) console.out << "; regime " << r.regime;
    console.out << "\nwrote " << o.output.string() << ": " << u_count << " x " << v_count << " grid, "
                << grid->positions.size() << " vertices, " << grid->faces.faceCount() << " quads\n";
    console.out << "constraints: position " << scientific(r.position_error) << ", tangent " << scientific(r.tangent_error)
                << " of the trimline data\n";
    // Next to a resonance the constraints still hold, but the surface bulges without bound between them.
    if (r.reach > kFarReach) {
      console.err << "warning: blend: the surface reaches " << scientific(r.reach)
                  << " times the size of its trimline data; (alpha, beta, gamma) lies near a resonance\n";
    }
  }
  if (report) *report = r;
  return kExitOk;
}

}  // namespace odeskin
