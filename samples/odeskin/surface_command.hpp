// SPDX-License-Identifier: MIT
// `odeskin surface NETWORK.json -o OUT.glb [--res U,V] [--shape R,E,L] [--obj] [--backend cpu|vulkan|auto]`: a network of
// C2 surface patches (thesis ch. 4; engine/surfaces, schema in docs/surfaces.md) tessellated into
// one welded, watertight mesh and written as a glTF 2.0 binary (and an OBJ with --obj).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "console.hpp"
#include "engine/core/result.hpp"

namespace odeskin {

struct SurfaceCommandOptions {
  std::filesystem::path network;
  std::filesystem::path output;   // .glb
  std::string resolution = "33,33";  // "U,V": samples per patch along u and v, each >= 2
  bool obj = false;               // also OUT.obj (same stem), the welded quads
  std::string shape;              // "RHO,ETA,LAMBDA" for every patch instead of the file's; empty: the file's
  std::string up = "y";           // the network's up axis (parseUpAxis); the GLB's node turns it to glTF's +y
  std::string backend = "cpu";    // cpu (double reference), vulkan (shaders/ode6_tessellate.comp), or auto:
                                  // vulkan, falling back to cpu (with a note) when any Vulkan step fails
  std::string device = "auto";
  bool validation = false;        // vulkan: Khronos validation layer, fail on any message
};

struct SurfaceReport {
  std::uint32_t rows = 0;
  std::uint32_t columns = 0;
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  std::size_t rim_edges = 0;      // edges with one face: the open rim only
  std::size_t warnings = 0;
  double tessellate_seconds = 0.0;
  std::string backend;            // the one that ran: cpu or vulkan
};

// Peak memory of the verb per welded vertex: double positions and normals, the quads, the glTF
// buffers and their serialisation. Measured (`/usr/bin/time -f %M odeskin -q surface vase.json
// --res R,R -o x.glb`): 3.44 GB for 12.0M vertices (R = 1000), 7.48 GB for 27.0M (R = 1500),
// about 290 bytes a vertex; the grid's own limit (kMaxTessellationVertices) allows 67M.
inline constexpr std::uint64_t kSurfaceBytesPerVertex = 320;

// kOutOfRange when `vertices` would need more than `memory_bytes` (0: unknown, then it fits):
// Linux grants such memory and kills the process, without a message, once it is used.
Status surfaceFitsInMemory(std::uint64_t vertices, std::uint64_t memory_bytes);

// Exit status as console.hpp: usage (2) for option errors (output not .glb, malformed --res or
// --shape, unknown backend); failure (1) for an unreadable or invalid network (one line naming the file and
// the field or element), no Vulkan device, validation messages, or a write error. Files are
// written atomically; on failure none is left behind.
int runSurfaceCommand(const SurfaceCommandOptions& options, Console& console, SurfaceReport* report = nullptr);

}  // namespace odeskin
