# tightrope measure --invariants (included by tests/CMakeLists.txt; label
# cli): the knot type of a made torus knot against its closed form, T(2,5):
# Delta = t^-2 - t^-1 + 1 - t + t^2, determinant 5; a link is refused with
# one line and exit status 2. The algebra's own tests: tests/topology/.
set(_inv_dir ${CMAKE_CURRENT_BINARY_DIR}/measure_invariants)
tr_engine_test(cli_measure_invariants 0 DIR ${_inv_dir}/table ONLY "k.vect;m.txt" OUT ${_inv_dir}/table/m.txt
  MATCH "\nalexander 1 -1 1 -1 1  determinant 5  crossings [0-9]+\n$"
  CMD sh -c "'${_tr}' make torus 2 5 --n 120 -o '${_inv_dir}/table/k.vect' && exec '${_tr}' measure --invariants '${_inv_dir}/table/k.vect' > '${_inv_dir}/table/m.txt'")
tr_engine_test(cli_measure_invariants_json 0 DIR ${_inv_dir}/json ONLY "k.vect;m.json" OUT ${_inv_dir}/json/m.json
  MATCH "\"alexander\": [[]1, -1, 1, -1, 1[]], \"determinant\": 5, \"crossings\": [0-9]+, \"projected_crossings\": [0-9]+, \"per_component\""
  CMD sh -c "'${_tr}' make torus -2 5 --n 120 -o '${_inv_dir}/json/k.vect' && exec '${_tr}' measure --json --invariants '${_inv_dir}/json/k.vect' > '${_inv_dir}/json/m.json'")
tr_engine_test(cli_measure_invariants_link 2 DIR ${_inv_dir}/link ONLY "h.vect"
  ERRMATCH "^tightrope measure: [^\n]*h[.]vect: knot invariants need one closed component; this curve has 2"
  CMD sh -c "'${_tr}' make hopf --n 64 -o '${_inv_dir}/link/h.vect' >/dev/null && exec '${_tr}' measure --invariants '${_inv_dir}/link/h.vect'")
