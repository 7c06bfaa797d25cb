// SPDX-License-Identifier: MIT
// `odeskin blend --example 3.15|3.16|3.17|3.18 [--alpha A --beta B --gamma G] [--res U,V]
// [--hermite | --spline N] -o OUT.obj`: one of the thesis's fourth-order ODE blending surfaces
// (ch. 3, engine/surfaces/) tessellated as a grid and written as OBJ. Vertex i*V + j is S(u_i, v_j)
// with u_i = i/(U-1) and v_j = 2 pi j/V; quads join the grid and wrap in v.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "console.hpp"
#include "engine/core/result.hpp"

namespace odeskin {

struct BlendCommandOptions {
  std::string example;                  // "3.15", "3.16", "3.17" or "3.18"
  std::optional<double> alpha;          // default: the example's thesis parameters
  std::optional<double> beta;
  std::optional<double> gamma;
  std::string res = "64,128";           // "U,V": samples across (u) and around (v) the blend
  bool hermite = false;                 // the cubic Hermite blend of Eq 3.19 instead of the ODE
  std::optional<int> spline_pieces;     // the clamped cubic spline approximation (Sec. 3.7) with N pieces
  std::filesystem::path output;         // .obj
};

struct BlendReport {
  std::uint32_t u_count = 0;
  std::uint32_t v_count = 0;
  double alpha = 0.0, beta = 0.0, gamma = 0.0;
  std::string regime;                   // empty for --hermite
  double position_error = 0.0;          // max |S - C| on both trimlines, of the data size
  double tangent_error = 0.0;           // max |S_u - Cbar| on both trimlines, of the data size
  double reach = 0.0;                   // max |S| over the grid, of the data size (positions and tangents)
};

// Peak memory of the verb per grid vertex (the double grid, the quads, the OBJ text). Measured
// (`/usr/bin/time -f %M odeskin -q blend --example 3.17 --res R,R -o x.obj`): 0.74 GB for 4M
// vertices (R = 2000), 2.94 GB for 16M (R = 4000), about 184 bytes a vertex.
inline constexpr std::uint64_t kBlendBytesPerVertex = 200;

// kOutOfRange when a grid of `vertices` would need more than `memory_bytes` (0: unknown, then it
// fits); Linux grants such memory and kills the process, without a message, once it is used.
Status blendFitsInMemory(std::uint64_t vertices, std::uint64_t memory_bytes);

// Exit status as console.hpp: usage (2) for an unknown or garbled example, a NaN or infinite
// parameter, a malformed --res (U < 2, V < 3, too many vertices), --hermite with shape parameters,
// --spline outside [1, 1000], or an output that is not .obj; failure (1) for parameters the ODE
// cannot use (alpha = 0, resonance; the message says why), a grid larger than the machine's memory
// and write errors. Nothing is written on
// failure; the OBJ is written atomically.
int runBlendCommand(const BlendCommandOptions& options, Console& console, BlendReport* report = nullptr);

}  // namespace odeskin
