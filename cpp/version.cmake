# cmake -DSOURCE_DIR=... -DFALLBACK=... -DOUTPUT=... -P version.cmake
# Write OUTPUT, a header defining GELX_VERSION: the source tree's git commit (with "-dirty" when
# files differ from it), or FALLBACK, the project version, outside a git clone. Run at every
# build; the file is rewritten only when the text changes, so an unchanged version rebuilds
# nothing.
execute_process(COMMAND git -C ${SOURCE_DIR} describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE version OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET
                RESULT_VARIABLE failed)
if(failed OR NOT version)
  set(version ${FALLBACK})
endif()
set(text "#pragma once\n#define GELX_VERSION \"${version}\"\n")
set(old "")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUTPUT} "${text}")
endif()
