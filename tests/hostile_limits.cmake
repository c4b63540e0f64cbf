# Limits that are limits (issue 45): --time-limit over roads, shuffles and a
# loaded machine, SIGHUP, the first checkpoint, a resumed run's goals; one
# test per case of tests/scripts/hostile_limits.sh. The load case runs two
# busy loops beside a 40 s run: it is serial, so that the suite's other
# tests neither slow it nor are slowed by it.
set(_limits_cases roads shuffles load huge_n refine_goal sighup first_checkpoint resume_goals)
foreach(c ${_limits_cases})
  add_test(NAME cli_limits_${c}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/hostile_limits.sh ${c} $<TARGET_FILE:tightrope>
            ${CMAKE_CURRENT_BINARY_DIR}/limits_${c})
  set_tests_properties(cli_limits_${c} PROPERTIES ENVIRONMENT "${TR_TEST_ENV}")
endforeach()
set_tests_properties(cli_limits_load PROPERTIES RUN_SERIAL TRUE)
