// SPDX-License-Identifier: MIT
// `odeskin surface NETWORK.json -o OUT.glb [--res U,V] [--shape R,E,L] [--obj] [--backend cpu|vulkan|auto]`: a network of
// C2 surface patches (thesis ch. 4; engine/surfaces, schema in docs/surfaces.md) tessellated into
// one welded, watertight mesh and written as a glTF 2.0 binary (and an OBJ with --obj).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "console.hpp"

namespace odeskin {

struct SurfaceCommandOptions {
  std::filesystem::path network;
  std::filesystem::path output;   // .glb
  std::string resolution = "33,33";  // "U,V": samples per patch along u and v, each >= 2
  bool obj = false;               // also OUT.obj (same stem), the welded quads
  std::string shape;              // "RHO,ETA,LAMBDA" for every patch instead of the file's; empty: the file's
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

// Exit status as console.hpp: usage (2) for option errors (output not .glb, malformed --res or
// --shape, unknown backend); failure (1) for an unreadable or invalid network (one line naming the file and
// the field or element), no Vulkan device, validation messages, or a write error. Files are
// written atomically; on failure none is left behind.
int runSurfaceCommand(const SurfaceCommandOptions& options, Console& console, SurfaceReport* report = nullptr);

}  // namespace odeskin
