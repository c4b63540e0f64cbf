# The Oclgrind leg (scripts/test.sh --oclgrind) catches what it is there
# for: each kernel of tests/oclgrind/broken.cl has one bug (an out-of-bounds
# write, a race between work-items, a write to a read-only buffer), and
# scripts/oclgrind_run.sh, which runs every OpenCL test in that leg, must
# fail on it with Oclgrind's report at the bug's line; the same program with
# the correct kernel must pass. Registered where Oclgrind is installed (that
# leg installs it), not in a sanitizer build: Oclgrind preloads its runtime,
# and ASan's must come first.
find_program(OCLGRIND_EXECUTABLE oclgrind)
if(OCLGRIND_EXECUTABLE AND NOT TIGHTROPE_SANITIZE)
  add_executable(oclgrind_broken ${CMAKE_CURRENT_SOURCE_DIR}/oclgrind/oclgrind_broken.c)
  target_link_libraries(oclgrind_broken PRIVATE tr_testlib tr_backend)
  add_dependencies(opencl_tests oclgrind_broken)
  set(_og_run bash ${CMAKE_SOURCE_DIR}/scripts/oclgrind_run.sh $<TARGET_FILE:oclgrind_broken>)
  set(_og_file "tests/oclgrind/broken.cl") # as Oclgrind names it: from the source tree
  add_test(NAME oclgrind_passes_fine_kernel COMMAND ${_og_run} fine)
  set_tests_properties(oclgrind_passes_fine_kernel PROPERTIES LABELS oclgrind
    ENVIRONMENT "${TR_TEST_ENV}")
  # the kind of report and the line of broken.cl it names; the run must fail
  set(_og_want_out_of_bounds "${_og_file}:21:[0-9]+: Invalid write of size 4")
  set(_og_want_race "${_og_file}:3[01]:[0-9]+: Read-write data race")
  set(_og_want_write_read_only "${_og_file}:42:[0-9]+: Invalid write to read-only buffer")
  foreach(_bug out_of_bounds race write_read_only)
    add_test(NAME oclgrind_catches_${_bug} COMMAND ${_og_run} ${_bug})
    set_tests_properties(oclgrind_catches_${_bug} PROPERTIES LABELS oclgrind
      ENVIRONMENT "${TR_TEST_ENV}"
      PASS_REGULAR_EXPRESSION "${_og_want_${_bug}}.*oclgrind_run: FAILED: Oclgrind found problems"
      FAIL_REGULAR_EXPRESSION "oclgrind_run: clean")
  endforeach()
endif()
if(TIGHTROPE_OCLGRIND AND NOT OCLGRIND_EXECUTABLE)
  message(FATAL_ERROR "-DTIGHTROPE_OCLGRIND=ON needs oclgrind (apt-get install oclgrind)")
endif()
