# tightrope analyze on open ropes (issue 23): the helix's curvature and torsion
# against their closed forms, the clasp, the anatomy of a clasp tightened by
# the reference (about 6 s), a rope too short, --mesh's tube (tests/scripts/analyze_open_cli.sh).
foreach(_case helix clasp clasp_tight short mesh)
  add_test(NAME analyze_open_${_case}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/analyze_open_cli.sh ${_case} $<TARGET_FILE:tightrope>
            ${CMAKE_CURRENT_BINARY_DIR}/analyze_open_${_case})
  set_tests_properties(analyze_open_${_case} PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
endforeach()
