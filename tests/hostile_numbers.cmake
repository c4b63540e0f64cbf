# Hostile-user checks of numbers and messages (issue 45), one test per case
# of tests/scripts/hostile_numbers.sh: curves far from the origin or in
# subnormal numbers, the KKT certificate of many components, and messages.
set(_hostile_number_cases far_tighten far_origin exact_shift subnormal kkt_many make_edges bom off_constraint kernel_build)
foreach(c ${_hostile_number_cases})
  add_test(NAME cli_hostile_${c}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/hostile_numbers.sh ${c} $<TARGET_FILE:tightrope>
            ${CMAKE_CURRENT_BINARY_DIR}/hostile_${c})
  set_tests_properties(cli_hostile_${c} PROPERTIES SKIP_RETURN_CODE 77 ENVIRONMENT "${TR_TEST_ENV}")
endforeach()
