# Hostile-user checks of tightrope batch (issue 45), one test per case of
# tests/scripts/hostile_batch.sh: a batch writing over another knot's start,
# records and checkpoints of another start, --merge of another knot under the
# same name, bad options found before anything runs.
set(_hostile_batch_cases cross stale_row stale_checkpoint resume_shuffles merge_other_start options_early)
foreach(c ${_hostile_batch_cases})
  add_test(NAME cli_hostile_batch_${c}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/hostile_batch.sh ${c} $<TARGET_FILE:tightrope>
            ${CMAKE_CURRENT_BINARY_DIR}/hostile_batch_${c})
  set_tests_properties(cli_hostile_batch_${c} PROPERTIES SKIP_RETURN_CODE 77 ENVIRONMENT "${TR_TEST_ENV}")
endforeach()
