# The curves committed for the seed paper's regime (bench/data/paper/, issue 48), each checked
# against the issue's targets and the published figures by a script independent of the run
# that made it (tests/scripts/paper_*.sh).
add_test(NAME paper_clasp_fine
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/paper_clasp_fine.sh $<TARGET_FILE:tightrope>
          ${CMAKE_SOURCE_DIR}/bench/data/paper/clasp_fine.vect.xz ${CMAKE_CURRENT_BINARY_DIR}/paper_clasp_fine)
set_tests_properties(paper_clasp_fine PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS "cli;paper")
