// SPDX-License-Identifier: MIT
// What `odeskin` does when it is interrupted: SIGINT, SIGTERM and SIGHUP remove the temporary file
// of any output being written (engine/core/pending_files.hpp), then end the process by the same
// signal, so the shell still sees "killed by SIGTERM" (exit status 128 + n) and no `.tmpNNNNNN`
// fragment is left beside the output.
#pragma once

namespace odeskin {

// Installs the handlers. A signal the process inherited as ignored (nohup, a background job of
// a non-interactive shell) stays ignored.
void removeTemporariesOnSignal();

}  // namespace odeskin
