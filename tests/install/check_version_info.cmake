# The test version.commit (tests/install/CMakeLists.txt): cmake/version_info.cmake, which writes the commit that
# ccal::version_commit() and `ccal --version` report.
#  - sources that are a git checkout: `git rev-parse --short HEAD` of them;
#  - sources that are not (an unpacked archive, here a folder inside the build tree, itself inside the
#    checkout, with an empty .git folder, so that git finds the checkout around it): "unknown", not the commit
#    of a repository around them;
#  - -DCOMMIT=<hash>: that hash; a COMMIT that is not a hash: refused.
foreach(argument SOURCE_DIR WORK_DIR GIT_EXECUTABLE)
  if(NOT DEFINED ${argument})
    message(FATAL_ERROR "check_version_info.cmake: -D${argument}=... is required")
  endif()
endforeach()
set(script ${SOURCE_DIR}/cmake/version_info.cmake)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/archive/.git)

function(commit_of source_dir commit_override out_var)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${source_dir} -DOUTPUT=${WORK_DIR}/version_info.cpp
                          -DVERSION=9.8.7 -DGIT_EXECUTABLE=${GIT_EXECUTABLE} -DCOMMIT=${commit_override}
                          -P ${script}
                  RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    set(${out_var} "error: ${err}" PARENT_SCOPE)
    return()
  endif()
  file(READ ${WORK_DIR}/version_info.cpp text)
  if(NOT text MATCHES "version\\(\\) noexcept { return \"9\\.8\\.7\"; }")
    message(FATAL_ERROR "version.commit: the generated file lacks version() = \"9.8.7\":\n${text}")
  endif()
  if(NOT text MATCHES "version_commit\\(\\) noexcept { return \"([^\"]*)\"; }")
    message(FATAL_ERROR "version.commit: the generated file has no version_commit():\n${text}")
  endif()
  set(${out_var} "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()

if(GIT_EXECUTABLE AND EXISTS ${SOURCE_DIR}/.git)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} rev-parse --short HEAD
                  OUTPUT_VARIABLE expected OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE status)
  if(status EQUAL 0)
    commit_of(${SOURCE_DIR} "" commit)
    if(NOT commit STREQUAL expected)
      message(FATAL_ERROR "version.commit: the checkout gave '${commit}', git rev-parse --short HEAD '${expected}'")
    endif()
  endif()
endif()
commit_of(${WORK_DIR}/archive "" commit)
if(NOT commit STREQUAL "unknown")
  message(FATAL_ERROR "version.commit: sources that are not a git checkout gave '${commit}', not 'unknown'")
endif()
commit_of(${WORK_DIR}/archive "0123abc" commit)
if(NOT commit STREQUAL "0123abc")
  message(FATAL_ERROR "version.commit: -DCOMMIT=0123abc gave '${commit}'")
endif()
commit_of(${WORK_DIR}/archive "abc\"; }" commit)
if(NOT commit MATCHES "^error: .*is not a git hash")
  message(FATAL_ERROR "version.commit: a COMMIT with a quote was not refused: '${commit}'")
endif()
