# Stands in for the Python tests when the module could not be built (python/CMakeLists.txt): fails with the
# reason, so that a missing dependency shows up as a failed test instead of a test that is not there.
message(FATAL_ERROR "python.bindings: the Python module ccal was not built because ${REASON} is missing; "
                    "install it (bash scripts/setup.sh) and reconfigure, or configure with -DCCAL_BUILD_PYTHON=OFF")
