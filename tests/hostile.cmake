# Hostile-user checks of the command line (issue 22), one test per case of
# tests/scripts/hostile_cli.sh.
set(_hostile_cases scale crossing same_file overwrite vect_line make_refuse args open_ends dev_zero devices analyze_stale analyze_layout)
foreach(c ${_hostile_cases})
  add_test(NAME cli_hostile_${c}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/hostile_cli.sh ${c} $<TARGET_FILE:tightrope>
            ${CMAKE_CURRENT_BINARY_DIR}/hostile_${c})
  set_tests_properties(cli_hostile_${c} PROPERTIES SKIP_RETURN_CODE 77 ENVIRONMENT "${TR_TEST_ENV}")
endforeach()
