# bench/ropelength_extrap from the command line (included by tests/CMakeLists.txt): a
# synthetic ladder from the closed form L = 32.7429345 + 915/N^2 - 3e8/N^4. The 1/N^2 fit
# alone leaves chi^2/dof > 4, so the fit with 1/N^4 is selected, and it gives the limit to
# 1e-10; bad input is exit 2 with one FILE:LINE line.
add_test(NAME cli_extrap_synthetic
  COMMAND $<TARGET_FILE:ropelength_extrap> ${CMAKE_CURRENT_SOURCE_DIR}/data/extrap_synthetic.tsv --ref 32.7429345)
set_tests_properties(cli_extrap_synthetic PROPERTIES
  PASS_REGULAR_EXPRESSION "selected: fit 2 [^\n]*\n.*L_inf = 32\\.742934500[0-9] \\+- [0-9.]+e-(0[7-9]|1[0-9])\n")
add_test(NAME cli_extrap_bad
  COMMAND ${CMAKE_COMMAND} -E env sh -c "printf '2400 32.7 0\\n' | '$<TARGET_FILE:ropelength_extrap>' -; test $? -eq 2")
