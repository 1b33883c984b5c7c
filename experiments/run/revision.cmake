# Writes revision.hpp with the source tree's git revision and dirty flag. Runs at every build
# (not only at configure time) so a record never names a stale revision; the file is rewritten
# only when its content changes, so an unchanged tree triggers no recompilation.
execute_process(COMMAND git -C ${SOURCE_DIR} rev-parse HEAD OUTPUT_VARIABLE rev OUTPUT_STRIP_TRAILING_WHITESPACE
                RESULT_VARIABLE rc ERROR_QUIET)
if(NOT rc EQUAL 0)
  set(rev "unknown")
endif()
execute_process(COMMAND git -C ${SOURCE_DIR} status --porcelain --untracked-files=no OUTPUT_VARIABLE status
                RESULT_VARIABLE rc2 ERROR_QUIET)
if(rc2 EQUAL 0 AND status STREQUAL "")
  set(dirty false)
else()
  set(dirty true)
endif()
set(content "#pragma once\n#define RAPID_GIT_REVISION \"${rev}\"\n#define RAPID_GIT_DIRTY ${dirty}\n")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} old)
endif()
if(NOT "${old}" STREQUAL "${content}")
  file(WRITE ${OUTPUT} "${content}")
endif()
