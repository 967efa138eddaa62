# The test install.consumer (tests/install/CMakeLists.txt): the package that `cmake --install` makes works.
#  1. cmake --install BUILD_DIR into a fresh prefix WORK_DIR/prefix, with every header of include/;
#  2. the installed CMake files name no path of the build machine (the source or build folder);
#  3. the consumer project (consumer/) configures with find_package(ccal) against the prefix alone, builds and
#     prints the nominal rate of the bundled example's 20 g run;
#  4. the installed `ccal --version` runs, and the manual page, the three shell completions and the
#     documentation the manual page names are installed (when CLI is true);
#  5. the installed Python package imports from the prefix with PYTHON, reports the same version and commit,
#     and its metadata (importlib.metadata) the project's version (when PYTHON is set).
foreach(argument BUILD_DIR WORK_DIR CONSUMER_DIR SOURCE_DIR GENERATOR CXX_COMPILER VERSION)
  if(NOT DEFINED ${argument} OR "${${argument}}" STREQUAL "")
    message(FATAL_ERROR "check_install.cmake: -D${argument}=... is required")
  endif()
endforeach()

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "install.consumer: ${what} failed (${status}):\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# 1. Install.
run_step("cmake --install ${BUILD_DIR} --prefix ${prefix}" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# The header tree as a whole, sub-folders included.
file(GLOB_RECURSE source_headers RELATIVE ${SOURCE_DIR}/include ${SOURCE_DIR}/include/*.hpp)
foreach(header ${source_headers})
  if(NOT EXISTS ${prefix}/include/${header})
    message(FATAL_ERROR "install.consumer: the header ${header} was not installed")
  endif()
endforeach()

# 2. Relocatable and free of build-machine paths: the prefix is computed from the files' own location, and
# neither the source folder nor the build folder is named (e.g. a compile definition CCAL_SOURCE_DIR="...").
file(GLOB package_files ${prefix}/lib*/cmake/ccal/*.cmake)
if(NOT package_files)
  message(FATAL_ERROR "install.consumer: no CMake package files under ${prefix}/lib*/cmake/ccal")
endif()
foreach(file ${package_files})
  file(READ ${file} text)
  foreach(path ${SOURCE_DIR} ${BUILD_DIR} ${prefix})
    string(FIND "${text}" "${path}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "install.consumer: ${file} names the build machine's path ${path}")
    endif()
  endforeach()
endforeach()

# 3. A consumer: configured against the prefix only (a package registry or an ambient prefix path could
# otherwise find the build tree), built and run.
set(consumer_build ${WORK_DIR}/consumer)
set(configure_args -S ${CONSUMER_DIR} -B ${consumer_build} -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release
                   -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
                   -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
if(CXX_LAUNCHER)
  list(APPEND configure_args "-DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_LAUNCHER}")
endif()
if(SANITIZE)
  # A library built with sanitizers needs their runtime in the program that links it.
  list(APPEND configure_args "-DCMAKE_CXX_FLAGS=-fsanitize=${SANITIZE}"
                             "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=${SANITIZE}")
endif()
run_step("configuring the consumer (find_package(ccal))" ${CMAKE_COMMAND} ${configure_args})
run_step("building the consumer" ${CMAKE_COMMAND} --build ${consumer_build})
run_step("running the consumer" ${consumer_build}/consumer)
# Ω = √(A g / R0) of the bundled example's "20g" run: A = 20, g = 9.8 m/s² and R0 = 2.5 m as in
# examples/wang_ren_2014.toml, so Ω = √78.4 = 8.854377448471462 rad/s. Printed to 9 decimals; the library's
# double differs from √78.4 by ~1e-15, far from changing the 9th decimal (the 10th is 4).
string(REPLACE "." "\\." version_regex "${VERSION}")
if(NOT step_output MATCHES "^ccal ${version_regex} \\(commit ([0-9a-f]+|unknown)\\)\nrate 8\\.854377448 rad/s\n$")
  message(FATAL_ERROR "install.consumer: the consumer printed\n${step_output}\nexpected\n"
                      "ccal ${VERSION} (commit <hash>|unknown)\nrate 8.854377448 rad/s")
endif()
string(REGEX MATCH "^[^\n]*" library_line "${step_output}")

# 4. The installed program.
if(CLI)
  run_step("${prefix}/bin/ccal --version" ${prefix}/bin/ccal --version)
  if(NOT step_output STREQUAL "${library_line}\n")
    message(FATAL_ERROR "install.consumer: installed ccal --version printed '${step_output}', "
                        "the library '${library_line}'")
  endif()
  foreach(file share/man/man1/ccal.1 share/bash-completion/completions/ccal share/zsh/site-functions/_ccal
               share/fish/vendor_completions.d/ccal.fish share/doc/ccal/README.md)
    if(NOT EXISTS ${prefix}/${file})
      message(FATAL_ERROR "install.consumer: ${file} was not installed")
    endif()
  endforeach()
  # Every page of docs/ the manual page names is installed where it says.
  file(READ ${prefix}/share/man/man1/ccal.1 man_page)
  string(REGEX MATCH "share/doc/ccal/docs[^\n]*" docs_line "${man_page}")
  foreach(page cli.md config.md model.md python.md tutorial.md)
    string(FIND "${docs_line}" "${page}" named)
    if(named EQUAL -1 OR NOT EXISTS ${prefix}/share/doc/ccal/docs/${page})
      message(FATAL_ERROR "install.consumer: the manual page names docs/${page} in '${docs_line}', which must "
                          "be installed as share/doc/ccal/docs/${page}")
    endif()
  endforeach()
endif()

# 5. The installed Python module, from the prefix alone (PYTHONPATH replaced, not extended).
if(PYTHON)
  if(NOT PYTHON_DIR)
    message(FATAL_ERROR "install.consumer: -DPYTHON_DIR=... (the module's folder under the prefix) is required")
  endif()
  set(module_dir ${prefix}/${PYTHON_DIR})
  run_step("importing the installed Python module from ${module_dir}"
           ${CMAKE_COMMAND} -E env PYTHONPATH=${module_dir} PYTHONNOUSERSITE=1 ${PYTHON} -c
           # (statements on lines of their own: a semicolon would split the CMake argument)
           "import ccal, ccal._ccal, importlib.metadata, os\nfor m in (ccal, ccal._ccal):\n    assert os.path.realpath(os.path.dirname(m.__file__)) == os.path.realpath('${module_dir}/ccal'), m.__file__\nprint(f'ccal {ccal.__version__} (commit {ccal.__commit__})')\nprint(len(ccal.bundled_example().runs))\nd = importlib.metadata.distribution('ccal')\nprint(d.version, d.metadata['Name'], d.read_text('INSTALLER').strip())\nprint(sorted(str(f) for f in d.files if str(f).startswith('ccal/') and f.hash is not None and f.size == os.path.getsize(f.locate())) == sorted('ccal/' + n for n in os.listdir('${module_dir}/ccal') if n != '__pycache__'))")
  # The same version and commit as the library; the bundled example's plan has six runs (5 g … 30 g); the
  # package's metadata gives the project's version, and its RECORD lists every file of the package with its
  # hash and size.
  set(expected "${library_line}\n6\n${VERSION} ccal cmake\nTrue\n")
  if(NOT step_output STREQUAL "${expected}")
    message(FATAL_ERROR "install.consumer: the installed Python module printed\n${step_output}\nexpected\n"
                        "${expected}")
  endif()
endif()
set(checked "the consumer")
if(CLI)
  string(APPEND checked ", the program")
endif()
if(PYTHON)
  string(APPEND checked ", the Python module")
endif()
message(STATUS "install.consumer: ${library_line}; ${checked} from ${prefix}")
