# Hostile-user checks of what the commands do to files (issue 45): outputs
# that are devices, FIFOs or stdout written in place; analyze never deleting
# or replacing its input or the user's files, all of a run's files or none
# (tests/scripts/hostile_files.sh). A few need root (mknod, mount) and skip
# without it.
set(_hostile_files_cases fifo_out device_out dev_full stdout_out analyze_input analyze_user_files no_gnuplot
    plots_signal disk_full)
foreach(c ${_hostile_files_cases})
  add_test(NAME files_hostile_${c}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/hostile_files.sh ${c} $<TARGET_FILE:tightrope>
            ${CMAKE_CURRENT_BINARY_DIR}/hostile_files_${c})
  set_tests_properties(files_hostile_${c} PROPERTIES SKIP_RETURN_CODE 77 ENVIRONMENT "${TR_TEST_ENV}")
endforeach()
