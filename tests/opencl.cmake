# tightrope devices and tightrope bench from the command line. Without an
# OpenCL device both still work (the reference is always listed and timed).
set(_tr $<TARGET_FILE:tightrope>)
add_test(NAME cli_devices COMMAND ${_tr} devices)
set_tests_properties(cli_devices PROPERTIES ENVIRONMENT "${TR_TEST_ENV}"
  PASS_REGULAR_EXPRESSION "reference +serial reference.*fp64 yes.*selected by")
add_test(NAME cli_devices_json COMMAND ${_tr} devices --json)
set_tests_properties(cli_devices_json PROPERTIES ENVIRONMENT "${TR_TEST_ENV}"
  PASS_REGULAR_EXPRESSION "\"devices\": \\[\n  {\"id\": \"reference\"")
add_test(NAME cli_devices_bad_option COMMAND ${_tr} devices --bogus)
set_tests_properties(cli_devices_bad_option PROPERTIES WILL_FAIL TRUE)
add_test(NAME cli_device_unknown COMMAND ${_tr} devices)
set_tests_properties(cli_device_unknown PROPERTIES
  ENVIRONMENT "${TR_TEST_ENV};TIGHTROPE_DEVICE=no-such-device-anywhere"
  PASS_REGULAR_EXPRESSION "selection 'no-such-device-anywhere': no device matches")
# every device validated against the reference before it is timed; a small N
add_test(NAME cli_bench_small COMMAND ${_tr} bench --n 300 --steps 2 --no-kernels --json)
set_tests_properties(cli_bench_small PROPERTIES ENVIRONMENT "${TR_TEST_ENV}"
  PASS_REGULAR_EXPRESSION "\"valid\": true, \"validation_diff\": [^,]+, \"steps\": 2"
  FAIL_REGULAR_EXPRESSION "\"valid\": false|\"error\"")
# the serial reference's other names (util/device_spec.h) time the reference,
# as tighten takes them, instead of failing as "not an opencl device"
add_test(NAME cli_bench_serial_name COMMAND ${_tr} bench --device serial --n 100 --steps 1 --no-kernels --json)
set_tests_properties(cli_bench_serial_name PROPERTIES ENVIRONMENT "${TR_TEST_ENV}"
  PASS_REGULAR_EXPRESSION "\"device\": \"serial reference[^\"]*\", \"n\": 100, \"valid\": true"
  FAIL_REGULAR_EXPRESSION "\"error\"")
# The JSON reports parse (CMake's own JSON parser), also where a figure does
# not exist: without a search the search time is null, not "nan".
set(_json_check ${CMAKE_CURRENT_SOURCE_DIR}/scripts/json_valid.cmake)
add_test(NAME cli_bench_json_no_search COMMAND ${CMAKE_COMMAND}
  "-DCMD=${_tr};bench;--n;300;--steps;1;--no-kernels;--no-search;--json"
  "-DMEMBER=results;0;contacts_s" -DTYPE=NULL -P ${_json_check})
set_tests_properties(cli_bench_json_no_search PROPERTIES ENVIRONMENT "${TR_TEST_ENV}")
add_test(NAME cli_devices_json_parses COMMAND ${CMAKE_COMMAND}
  "-DCMD=${_tr};devices;--json" "-DMEMBER=devices;0;id" -DTYPE=STRING -P ${_json_check})
set_tests_properties(cli_devices_json_parses PROPERTIES ENVIRONMENT "${TR_TEST_ENV}")
# bench's numbers are whole tokens, and a device that does not exist is
# refused before any other device is timed
add_test(NAME cli_bench_bad_steps COMMAND ${_tr} bench --device reference --n 300 --steps 2abc)
set_tests_properties(cli_bench_bad_steps PROPERTIES PASS_REGULAR_EXPRESSION "^tightrope bench: bad --steps '2abc'\n$")
add_test(NAME cli_bench_bad_n_trailing COMMAND ${_tr} bench --device reference --n 300,)
set_tests_properties(cli_bench_bad_n_trailing PROPERTIES PASS_REGULAR_EXPRESSION "^tightrope bench: bad --n list")
add_test(NAME cli_bench_bad_device COMMAND ${_tr} bench --device reference --device no-such-device-xyz --n 300 --steps 1)
set_tests_properties(cli_bench_bad_device PROPERTIES
  PASS_REGULAR_EXPRESSION "^tightrope bench: no device matches 'no-such-device-xyz'[^\n]*\n$")
add_test(NAME cli_bench_bad_n COMMAND ${_tr} bench --n 12,abc)
set_tests_properties(cli_bench_bad_n PROPERTIES WILL_FAIL TRUE)
# from a tight trefoil resampled to N: a tight curve has contacts to list
add_test(NAME cli_bench_tight_start COMMAND ${_tr} bench --device reference --n 600 --steps 2 --no-kernels
  --json --start ${CMAKE_SOURCE_DIR}/bench/data/trefoil_2400.vect)
set_tests_properties(cli_bench_tight_start PROPERTIES
  PASS_REGULAR_EXPRESSION "\"pairs\": [1-9][0-9]*" FAIL_REGULAR_EXPRESSION "\"error\"")
# The device against the reference on a tight state (many struts active in
# the CG, jt_vertex over the active adjacency): the bench's validation step
# holds the positions to 1e-10 of |x| and reports "valid": false otherwise.
# Without an OpenCL device the results hold the reference alone: a pass.
add_test(NAME cli_bench_tight_start_opencl COMMAND ${_tr} bench --n 2000 --steps 1 --no-kernels
  --json --start ${CMAKE_SOURCE_DIR}/bench/data/trefoil_2400.vect)
set_tests_properties(cli_bench_tight_start_opencl PROPERTIES ENVIRONMENT "${TR_TEST_ENV}"
  PASS_REGULAR_EXPRESSION "OpenCL[^}]*\"valid\": true[^}]*\"pairs\": [1-9]|\"results\": \\[\n  {\"device\": \"serial reference[^\n]*\n \\]}"
  FAIL_REGULAR_EXPRESSION "\"error\"|\"valid\": false")
add_test(NAME cli_bench_bad_contacts COMMAND ${_tr} bench --contacts 1.5,0.1)
set_tests_properties(cli_bench_bad_contacts PROPERTIES
  PASS_REGULAR_EXPRESSION "bad --contacts '1.5,0.1'")
# Every edge-block solver of the preconditioner on whatever device there is
# (by default the twisted factorisation on CPU devices such as PoCL, PCR on
# GPUs), each against the serial reference.
foreach(_solver pcr-group pcr-levels thomas twisted)
  add_test(NAME test_opencl_backend_${_solver}
    COMMAND ${TR_CL_TEST_LAUNCH} $<TARGET_FILE:test_opencl_backend>)
  set_tests_properties(test_opencl_backend_${_solver} PROPERTIES SKIP_RETURN_CODE 77
    ENVIRONMENT "${TR_CL_TEST_ENV};TIGHTROPE_CL_TRIDIAG=${_solver}"
    WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR} LABELS backend/opencl
    PASS_REGULAR_EXPRESSION "\\[${_solver}\\]: pairs.*all checks passed|skipped")
endforeach()
# The other launch shape of the index-looping kernels (common.clh TR_ITEMS):
# one index per work-item, as on a GPU, where the default on CPU devices is
# a block of indices per work-item.
foreach(_t test_opencl_backend test_opencl_tree)
  add_test(NAME ${_t}_items_one COMMAND ${TR_CL_TEST_LAUNCH} $<TARGET_FILE:${_t}>)
  set_tests_properties(${_t}_items_one PROPERTIES SKIP_RETURN_CODE 77
    ENVIRONMENT "${TR_CL_TEST_ENV};TIGHTROPE_CL_ITEMS=one" LABELS backend/opencl
    WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
    PASS_REGULAR_EXPRESSION "all checks passed|skipped")
endforeach()
add_test(NAME cli_bench_bad_items COMMAND ${_tr} bench --n 300 --steps 1 --device opencl)
set_tests_properties(cli_bench_bad_items PROPERTIES
  ENVIRONMENT "${TR_TEST_ENV};TIGHTROPE_CL_ITEMS=bogus"
  PASS_REGULAR_EXPRESSION "TIGHTROPE_CL_ITEMS='bogus': use one or blocks")
add_test(NAME cli_bench_bad_tridiag COMMAND ${_tr} bench --n 300 --steps 1 --device opencl)
set_tests_properties(cli_bench_bad_tridiag PROPERTIES
  ENVIRONMENT "${TR_TEST_ENV};TIGHTROPE_CL_TRIDIAG=bogus"
  PASS_REGULAR_EXPRESSION "TIGHTROPE_CL_TRIDIAG='bogus': use thomas, twisted, pcr")
