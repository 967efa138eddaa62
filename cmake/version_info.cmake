# Writes the library's version and the git commit of the sources to OUTPUT (a .cpp from
# cmake/version_info.cpp.in). Run by the build on every invocation (target ccal_version_info), so that a new
# HEAD is picked up without re-running CMake; the file is only rewritten when its text changes, so an unchanged
# commit rebuilds nothing and a new one recompiles this one file and relinks.
#   cmake -DSOURCE_DIR=<sources> -DOUTPUT=<file.cpp> -DVERSION=<x.y.z> [-DGIT_EXECUTABLE=<git>]
#         [-DCOMMIT=<hash>] -P version_info.cmake
# COMMIT, when not empty, is used as given (a build from a source archive whose commit is known). Otherwise the
# commit is `git rev-parse --short HEAD` of SOURCE_DIR if SOURCE_DIR is the top of a git work tree (not merely
# inside one, as an unpacked archive within another repository would be), else "unknown".
foreach(argument SOURCE_DIR OUTPUT VERSION)
  if(NOT DEFINED ${argument} OR "${${argument}}" STREQUAL "")
    message(FATAL_ERROR "version_info.cmake: -D${argument}=... is required")
  endif()
endforeach()

set(CCAL_VERSION "${VERSION}")
set(CCAL_COMMIT "unknown")
if(DEFINED COMMIT AND NOT "${COMMIT}" STREQUAL "")
  set(CCAL_COMMIT "${COMMIT}")
elseif(GIT_EXECUTABLE AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SOURCE_DIR}" rev-parse --show-toplevel --short HEAD
                  RESULT_VARIABLE git_status OUTPUT_VARIABLE git_output ERROR_QUIET
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(git_status EQUAL 0)
    string(REPLACE "\n" ";" git_lines "${git_output}")
    list(LENGTH git_lines git_line_count)
    if(git_line_count EQUAL 2)
      list(GET git_lines 0 git_toplevel)
      list(GET git_lines 1 git_commit)
      file(REAL_PATH "${git_toplevel}" git_toplevel)
      file(REAL_PATH "${SOURCE_DIR}" source_dir_real)
      if(git_toplevel STREQUAL source_dir_real AND git_commit MATCHES "^[0-9a-f]+$")
        set(CCAL_COMMIT "${git_commit}")
      endif()
    endif()
  endif()
endif()
if(NOT CCAL_COMMIT MATCHES "^[0-9A-Za-z._-]+$")
  message(FATAL_ERROR "version_info.cmake: commit '${CCAL_COMMIT}' is not a git hash (letters, digits, . _ -)")
endif()

get_filename_component(template "${CMAKE_CURRENT_LIST_DIR}/version_info.cpp.in" ABSOLUTE)
file(READ "${template}" text)
string(CONFIGURE "${text}" text @ONLY)
set(previous "")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" previous)
endif()
if(NOT previous STREQUAL text)
  file(WRITE "${OUTPUT}" "${text}")
endif()
