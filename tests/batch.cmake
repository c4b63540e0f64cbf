# tightrope batch (tests/scripts/batch_cli.sh): killed and restarted, SIGTERM, a second batch
# over a knot the first is running, bad manifests, a folder with --compare, --job/--jobs, --merge, --retry, the
# GNU parallel route (skipped where parallel is not installed) and scripts/slurm_batch.sh run
# as its array tasks would run it; manifests by name (bench/names_manifest.sh, --compare knotinfo).
foreach(_case kill_resume sigterm lock manifest_errors folder_compare jobs merge retry parallel slurm manifests)
  add_test(NAME cli_batch_${_case}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/batch_cli.sh ${_case} $<TARGET_FILE:tightrope>
            ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/batch_${_case})
  set_tests_properties(cli_batch_${_case} PROPERTIES SKIP_RETURN_CODE 77
    ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
endforeach()
# parallel runs two tightenings at once: alone, so that ctest -j2 does not add a third
set_tests_properties(cli_batch_parallel PROPERTIES RUN_SERIAL TRUE)
# scripts/gallery.py: a batch's results as a release folder, its page opened in a headless
# browser (tests/scripts/gallery_cli.sh)
add_test(NAME cli_batch_gallery
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/gallery_cli.sh $<TARGET_FILE:tightrope> ${CMAKE_SOURCE_DIR}
          ${CMAKE_CURRENT_BINARY_DIR}/batch_gallery)
set_tests_properties(cli_batch_gallery PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
# the knot table's data release in the repository (data/release/knots-to-8): every curve
# measured, identified and on the page, independently of the runs that made it
add_test(NAME release_knots_to_8
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/release_check.sh $<TARGET_FILE:tightrope>
          ${CMAKE_SOURCE_DIR}/data/release/knots-to-8 ${CMAKE_CURRENT_BINARY_DIR}/release_knots_to_8)
set_tests_properties(release_knots_to_8 PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
