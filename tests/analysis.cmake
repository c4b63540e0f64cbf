# tightrope analyze: the portrait of the tight trefoil, plots, --plots refused without
# gnuplot, plots of coarse knots, PNGs written atomically, the tube pictures, the paper's 9-cycles on a trefoil our engine tightened, refused arguments and option values, no output directory for a bad input (tests/scripts/analyze_cli.sh).
foreach(_case trefoil no_gnuplot plots plots_coarse plots_origin plots_atomic tube cycles usage options nodir)
  add_test(NAME analyze_cli_${_case}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/analyze_cli.sh ${_case} $<TARGET_FILE:tightrope>
            ${CMAKE_CURRENT_SOURCE_DIR}/data ${CMAKE_CURRENT_BINARY_DIR}/analyze_${_case}
            ${CMAKE_SOURCE_DIR}/bench/data/trefoil_1600.vect)
  set_tests_properties(analyze_cli_${_case} PROPERTIES SKIP_RETURN_CODE 77 ENVIRONMENT "${TR_TEST_ENV}")
endforeach()
