// Which SUMO client library the SUMO-facing env code is compiled against, and the namespace that
// keeps the two builds apart.
//
// The driving scenarios' SUMO-facing sources (envs/CMakeLists.txt: RAPID_SUMO_SOURCES) are compiled
// twice from the same files:
//   rapid_envs      against libsumo (SUMO in this process; every run, sweep and test uses it),
//   rapid_envs_gui  against libtraci with RAPID_LIBTRACI defined (SUMO's client library with the
//                   same API, driving a separate sumo-gui process: `rapid rollout --gui`).
// Their classes live in an inline namespace named after the backend, so both builds link into the
// one `rapid` binary without clashing, while code compiled without RAPID_LIBTRACI keeps writing
// rapid::DrivingEnv, rapid::Road, … and gets the libsumo ones. The libsumo path is unchanged:
// the same calls, resolved at compile time.
#pragma once

#ifdef RAPID_LIBTRACI
#define RAPID_SUMO_BACKEND traci_backend
#else
#define RAPID_SUMO_BACKEND libsumo_backend
#endif

// Opens/closes the backend's namespace inside namespace rapid.
#define RAPID_SUMO_BACKEND_BEGIN inline namespace RAPID_SUMO_BACKEND {
#define RAPID_SUMO_BACKEND_END }
