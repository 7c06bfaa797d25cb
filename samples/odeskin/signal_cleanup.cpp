// SPDX-License-Identifier: MIT
#include "signal_cleanup.hpp"

#include <csignal>

#include "engine/core/pending_files.hpp"

namespace odeskin {
namespace {

void removeTemporariesAndDie(int signal_number) {
  removePendingFiles();
  // SA_RESETHAND restored the default action, and the signal is blocked until this returns, so the
  // raised copy ends the process as the original would have.
  std::raise(signal_number);
}

}  // namespace

void removeTemporariesOnSignal() {
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old_action {};
    if (::sigaction(signal_number, nullptr, &old_action) != 0 || old_action.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = removeTemporariesAndDie;
    action.sa_flags = SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    ::sigaction(signal_number, &action, nullptr);
  }
}

}  // namespace odeskin
