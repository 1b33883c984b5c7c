# The include rule of the source tree (docs/design.md, "Layers"), checked by CTest: each folder
# may include only itself and the folders listed for it, so dependencies point one way:
#
#   experiments/cli  →  experiments/report  →  experiments/sweep  →  experiments/run  →  envs, algos  →  core
#   experiments/bench (beside report and sweep) → experiments/run; only experiments/cli uses bench
#   experiments/tune → experiments/report (its formats), experiments/sweep; only experiments/cli uses tune
#   python (the Python module) → experiments/run, beside experiments/cli
#
# One line "FOLDER: MAY INCLUDE..." per folder. An include of a path under none of these folders (a
# system header, the generated revision.hpp) is not ours and not checked; a C++ file directly in
# experiments/ belongs in one of its subsystem folders and fails the check.
#
#   cmake -DROOT=<source tree> -P tests/include_layers.cmake
cmake_minimum_required(VERSION 3.25)

set(rules
  "core:"
  "envs: core"
  "algos: core"
  "experiments/run: core envs algos"
  "experiments/sweep: core envs algos experiments/run"
  "experiments/report: core envs algos experiments/run experiments/sweep"
  "experiments/bench: core envs algos experiments/run"
  "experiments/tune: core envs algos experiments/run experiments/sweep experiments/report"
  "experiments/cli: core envs algos experiments/run experiments/sweep experiments/report experiments/bench experiments/tune"
  "python: core envs algos experiments/run")

if(NOT ROOT)
  message(FATAL_ERROR "include_layers.cmake: pass -DROOT=<source tree>")
endif()

set(folders "")
foreach(rule IN LISTS rules)
  string(REGEX MATCH "^([^:]+):(.*)$" _ "${rule}")
  set(folder "${CMAKE_MATCH_1}")
  string(STRIP "${CMAKE_MATCH_2}" allowed)
  separate_arguments(allowed UNIX_COMMAND "${allowed}")
  list(APPEND folders "${folder}")
  set("allowed_${folder}" ${folder} ${allowed})
endforeach()

# The folder a path belongs to: the longest listed folder it lies in ("" if none).
function(folder_of path out)
  set(best "")
  foreach(folder IN LISTS folders)
    string(LENGTH "${folder}" n)
    string(LENGTH "${best}" m)
    if(path MATCHES "^${folder}/" AND n GREATER m)
      set(best "${folder}")
    endif()
  endforeach()
  set(${out} "${best}" PARENT_SCOPE)
endfunction()

set(violations "")
set(checked 0)
file(GLOB_RECURSE sources RELATIVE "${ROOT}" "${ROOT}/core/*" "${ROOT}/envs/*" "${ROOT}/algos/*" "${ROOT}/experiments/*" "${ROOT}/python/*")
foreach(file IN LISTS sources)
  if(NOT file MATCHES "\\.(cpp|hpp|h)$")
    continue()
  endif()
  math(EXPR checked "${checked} + 1")
  folder_of("${file}" from)
  if(from STREQUAL "")
    list(APPEND violations "${file}: in no layer folder (code in experiments/ belongs in run, sweep, report, bench or cli)")
    continue()
  endif()
  file(STRINGS "${ROOT}/${file}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]+)\".*$" "\\1" target "${line}")
    folder_of("${target}" to)
    if(to STREQUAL "")
      continue()
    endif()
    if(NOT to IN_LIST "allowed_${from}")
      list(JOIN "allowed_${from}" ", " allowed)
      list(APPEND violations "${file} includes ${target}: ${from} may include only ${allowed}")
    endif()
  endforeach()
endforeach()

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "includes that break the layering (docs/design.md, \"Layers\"):\n  ${text}")
endif()
message(STATUS "include layers: ${checked} files, every include points down")
