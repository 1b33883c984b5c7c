// Temporary files that a stop signal must not leave behind. A process killed by SIGINT (Ctrl-C),
// SIGTERM or SIGHUP runs no destructor, so a file its objects would have removed (a driving
// scenario's route file in /tmp) stayed (issue #67). A registered path is unlinked by a handler for
// those three signals, which then lets the signal end the process as it would have, so the exit
// status still says "killed by SIGINT". The handlers are installed only where the signal's
// disposition is the default one: a process that handles a stop signal itself (the sweep runner,
// a report being written, Python's Ctrl-C) keeps its own handling.
#pragma once

#include <string>

namespace rapid {

// Unlinks `path` if a stop signal arrives before forget_on_stop(path). Thread-safe; a path longer
// than the registry holds, or one registered when the registry is full, is left to its owner.
void remove_on_stop(const std::string& path);
// The owner removed `path` itself (or keeps it): the handler no longer touches it.
void forget_on_stop(const std::string& path);

}  // namespace rapid
