# tightrope tighten runs the polish stage at the finest level (its line in
# the certificate) and --no-polish leaves it out. No timings are asserted.
# Both outputs carry their KKT certificate (N = 72: computed by default);
# --no-kkt leaves a line saying it was not computed.
set(_pol_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_polish)
tr_engine_test(tighten_polish 0 DIR ${_pol_dir}/on ONLY "s.vect;t.vect" OUT ${_pol_dir}/on/t.vect
  MATCH "\n# stop [a-z-]+\n# rescaled to thickness 1\n# knot type kept: Alexander polynomial 1 -1 1, determinant 3, [^\n]*\n# kkt_residual [0-9]\\.[0-9]+e[-+][0-9]+ [^\n]*\n# polish accepted: ropelength [0-9.]+ -> [0-9.]+ in [0-9.]+ s\n1 72 0"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_pol_dir}/on/s.vect' && exec '${_tr}' tighten '${_pol_dir}/on/s.vect' -o '${_pol_dir}/on/t.vect' --time-limit 2 --quiet --device reference")
tr_engine_test(tighten_no_polish 0 DIR ${_pol_dir}/off ONLY "s.vect;t.vect" OUT ${_pol_dir}/off/t.vect
  MATCH "\n# stop [a-z-]+\n# rescaled to thickness 1\n# knot type kept: Alexander polynomial 1 -1 1, determinant 3, [^\n]*\n# kkt_residual not computed [(]--no-kkt[)]\n1 72 0"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_pol_dir}/off/s.vect' && exec '${_tr}' tighten '${_pol_dir}/off/s.vect' -o '${_pol_dir}/off/t.vect' --time-limit 1 --no-polish --no-kkt --quiet --device reference")
# --newton: the second-order solver takes the polish's place at the finest
# level (its own line in the certificate, no polish line) and leaves a curve
# at thickness 1 (the engine's settle, then the oracle's measure).
tr_engine_test(tighten_newton 0 DIR ${_pol_dir}/newton ONLY "s.vect;t.vect" OUT ${_pol_dir}/newton/t.vect
  MATCH "\n# kkt_residual [0-9]\\.[0-9]+e[-+][0-9]+ [^\n]*\n# newton accepted: ropelength [0-9.]+ -> [0-9.]+ in [0-9.]+ s, [0-9]+ steps\n1 72 0"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_pol_dir}/newton/s.vect' && exec '${_tr}' tighten '${_pol_dir}/newton/s.vect' -o '${_pol_dir}/newton/t.vect' --time-limit 3 --newton --quiet --device reference")
# The solver's route (tests/scripts/newton_route.sh): a tightened knot
# resampled finer by --n goes to the solver first and ends shorter; SIGINT
# while it runs stops the run promptly with a curve written.
foreach(c refine sigint auto)
  add_test(NAME tighten_newton_route_${c}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/newton_route.sh ${c} $<TARGET_FILE:tightrope>
            ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/newton_route_${c})
  set_tests_properties(tighten_newton_route_${c} PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
endforeach()
