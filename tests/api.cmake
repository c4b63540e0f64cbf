# The public C API and the shared library (cmake/Library.cmake), label api:
# examples/trefoil.c built against the installed library through pkg-config
# and find_package(Tightrope) and run (tests/scripts/install_example.sh);
# the unit tests of host/api are tests/api/test_*.c.
add_test(NAME api_install_example
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/install_example.sh ${CMAKE_BINARY_DIR} ${CMAKE_SOURCE_DIR}
          ${CMAKE_CURRENT_BINARY_DIR}/api_install_example)
# Under the sanitizers (scripts/test.sh --sanitize) the library needs the
# ASan runtime loaded first, which a program built without them (the
# example, python3) does not do: it is preloaded (into the examples alone,
# TR_EXAMPLE_PRELOAD, not the compilers the script also runs).
set(TR_API_TEST_ENV "${TR_TEST_ENV}")
set(_example_env "${TR_TEST_ENV}")
if(TIGHTROPE_SANITIZE)
  execute_process(COMMAND ${CMAKE_C_COMPILER} -print-file-name=libasan.so OUTPUT_VARIABLE _asan
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  execute_process(COMMAND ${CMAKE_C_COMPILER} -print-file-name=libubsan.so OUTPUT_VARIABLE _ubsan
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  list(APPEND TR_API_TEST_ENV "LD_PRELOAD=${_asan}:${_ubsan}")
  list(APPEND _example_env "TR_EXAMPLE_PRELOAD=${_asan}:${_ubsan}")
endif()
set_tests_properties(api_install_example PROPERTIES ENVIRONMENT "${_example_env};TIGHTROPE_DEVICE=reference"
  LABELS api)
