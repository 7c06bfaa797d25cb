// SPDX-License-Identifier: MIT
// `odeskin fit POSES... -o ASSET`: example poses in, a .odsk asset out (runFitPipeline, saveAsset).
// Inputs: K >= 2 OBJ poses of one mesh (optionally --bind REST.obj), or one .gltf/.glb with
// --times / --targets, or OBJ poses with a libigl rig (--rig SKELETON.tgf --bind REST.obj
// [--weights W.dmat] [--transforms P1.Tmat,...]).
#pragma once

#include "console.hpp"
#include "fit_options.hpp"

namespace odeskin {

// Exit status as console.hpp: usage (2) for option errors, failure (1) for unreadable inputs, a
// failed fit or an unwritable output (nothing is left at `output` then).
int runFitCommand(const FitCommandOptions& options, Console& console);

}  // namespace odeskin
