# The Python package (python/, label python): its pytest tests against this
# build's libtightrope.so and command line (tests/scripts/python_tests.sh;
# skipped, 77, without a python3 that has numpy and pytest). The installed
# package (pip install ./python in a fresh venv) is scripts/test.sh --python.
add_test(NAME python_pytest
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/python_tests.sh $<TARGET_FILE:tightrope_shared>
          $<TARGET_FILE:tightrope> ${CMAKE_SOURCE_DIR})
# (after tests/api.cmake: its TR_API_TEST_ENV preloads the sanitizers' runtime;
# the interpreter's own allocations are not ours to check for leaks)
set(_py_env "${TR_API_TEST_ENV}")
if(TIGHTROPE_SANITIZE)
  list(APPEND _py_env "ASAN_OPTIONS=detect_leaks=0")
endif()
set_tests_properties(python_pytest PROPERTIES ENVIRONMENT "${_py_env}" LABELS python SKIP_RETURN_CODE 77)
