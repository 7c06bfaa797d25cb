// SPDX-License-Identifier: MIT
// `odeskin rig MESH... -o SKELETON.tgf [--weights W.dmat] [--template humanoid|quadruped|auto|none]
// [--gltf OUT.glb] [--png OUT.png]` (issue 8): a skeleton and skinning weights from the mesh's
// iso-parametric curves (thesis ch. 5, engine/rig/curve_rig.hpp). The first MESH is the bind
// mesh; further meshes (same vertices and faces) are example poses whose bends place joints a
// straight bind pose does not show (Sec. 5.4). Or one .gltf/.glb: its mesh is the bind mesh, and
// --times / --targets give the example poses. Outputs are the libigl formats of the shared data;
// --gltf writes the mesh with its new skin, keeping a glTF input's seams, UVs and materials.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "console.hpp"

namespace odeskin {

inline constexpr int kMaxRigRepeats = 100000;

struct RigCommandOptions {
  std::vector<std::filesystem::path> meshes;  // OBJ: the bind mesh, then example poses; or one .gltf/.glb
  std::string mesh;                           // glTF: the mesh node (default: the first skinned mesh, else the first)
  std::string animation;                      // glTF: for --times (default: the first)
  std::vector<double> times;                  // glTF: example poses at these animation times (seconds)
  std::vector<int> targets;                   // glTF: example poses with these morph targets at weight 1
  std::filesystem::path output;               // .tgf (required)
  std::filesystem::path weights;              // .dmat, optional
  std::filesystem::path gltf;                 // .glb, optional: mesh, skin and joints at the bind pose
  std::filesystem::path png;                  // .png, optional: curves and skeleton over the mesh (Vulkan)
  std::string template_kind = "auto";         // auto | humanoid | quadruped | none
  std::string curves = "auto";                // auto (loops on quad meshes, else levels) | levels (geodesic rings) |
                                              // cuts (plane cuts of the parts) | loops (quad edge loops, ray-and-fan)
  double angle_deg = 20.0;                    // the turn that makes a joint
  std::string up = "y";                       // the mesh's up axis (templates, picture)
  std::filesystem::path compare;              // a ground-truth .tgf: print the joint errors against it
  double azimuth_deg = 30.0;                  // --png camera angle about the up axis
  int repeat = 1;                             // runs (<= kMaxRigRepeats); timings are the medians
  std::string device = "auto";                // for --png
};

// Exit status as console.hpp: usage (2) for option errors (a missing -o, wrong extensions, glTF
// options without a glTF input, a glTF file with other meshes, an
// unknown template or curve source, an angle outside (0, 180), repeat outside [1, kMaxRigRepeats]); failure (1) for
// unreadable or mismatched meshes, a mesh no skeleton can be read from, write errors. Prints the
// bone count, the template, and the time of each stage (Table 5.1's vertex identification and
// skeleton creation, then the weights).
int runRigCommand(const RigCommandOptions& options, Console& console);

}  // namespace odeskin
