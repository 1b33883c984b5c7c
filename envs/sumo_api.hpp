// The SUMO API the env sources call, as `sumo_api::Vehicle`, `sumo_api::Simulation`, …: libsumo,
// or libtraci when compiled with RAPID_LIBTRACI (envs/sumo_backend.hpp). Both declare the same
// classes from the same headers; their data types and exceptions (libsumo::TraCIException,
// libsumo::TraCIPosition, …) are shared. Include it in .cpp files only.
#pragma once

#include "envs/sumo_backend.hpp"

#ifdef RAPID_LIBTRACI
#include <libsumo/libtraci.h>
namespace rapid {
namespace sumo_api = ::libtraci;
}
#else
#include <libsumo/libsumo.h>
namespace rapid {
namespace sumo_api = ::libsumo;
}
#endif
