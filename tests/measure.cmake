# 'tightrope measure' from the command line (included by tests/CMakeLists.txt).
set(_measure_check ${CMAKE_CURRENT_SOURCE_DIR}/cli/measure_check.cmake)
foreach(mode json array struts dir)
  add_test(NAME cli_measure_${mode}
    COMMAND ${CMAKE_COMMAND} -DTR=$<TARGET_FILE:tightrope> -DMODE=${mode}
            -DDATA=${CMAKE_CURRENT_SOURCE_DIR}/data -DWORK=${CMAKE_CURRENT_BINARY_DIR}/measure_${mode}
            -P ${_measure_check})
endforeach()
# Every broken file of the readers' corpus: exit 2, one FILE:LINE line, no --struts file.
file(GLOB _measure_bad CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/bad/*)
foreach(bad ${_measure_bad})
  get_filename_component(_n ${bad} NAME)
  string(MAKE_C_IDENTIFIER ${_n} _id)
  add_test(NAME cli_measure_bad_${_id}
    COMMAND ${CMAKE_COMMAND} -DTR=$<TARGET_FILE:tightrope> -DMODE=bad -DFILE=${bad}
            -DDATA=${CMAKE_CURRENT_SOURCE_DIR}/data -DWORK=${CMAKE_CURRENT_BINARY_DIR}/measure_bad_${_id}
            -P ${_measure_check})
endforeach()
# --kkt: a regular 101-gon certified at its own thickness (its MinRad) is
# critical, residual ~1e-14 (test_kkt.c has the closed forms); a bad band is
# refused with one line.
set(_kkt_dir ${CMAKE_CURRENT_BINARY_DIR}/measure_kkt)
tr_engine_test(cli_measure_kkt 0 DIR ${_kkt_dir}/ok ONLY "c.vect;m.txt" OUT ${_kkt_dir}/ok/m.txt
  MATCH "KKT residual [0-9][.][0-9]+e-(1[0-9]|[2-9][0-9]) [(]band 1e-06, [^\n]*multipliers optimal[)]\n$"
  CMD sh -c "'${_tr}' make circle --radius 5 --n 101 -o '${_kkt_dir}/ok/c.vect' && exec '${_tr}' measure --kkt '${_kkt_dir}/ok/c.vect' > '${_kkt_dir}/ok/m.txt'")
tr_engine_test(cli_measure_kkt_json 0 DIR ${_kkt_dir}/json ONLY "c.vect;m.json" OUT ${_kkt_dir}/json/m.json
  MATCH "\"kkt\": {\"residual\": [0-9][.][0-9]+e-(1[0-9]|[2-9][0-9]), \"band\": 1[.0-9]*e-05, [^}]*\"converged\": true}"
  CMD sh -c "'${_tr}' make circle --radius 5 --n 101 -o '${_kkt_dir}/json/c.vect' && exec '${_tr}' measure --json --kkt-band 1e-5 '${_kkt_dir}/json/c.vect' > '${_kkt_dir}/json/m.json'")
tr_engine_test(cli_measure_kkt_bad_band 2 CMD ${_tr} measure --kkt-band -1 ${CMAKE_CURRENT_SOURCE_DIR}/data/engine_overlap.tsv)
# --kkt-forces: per vertex, the pull of a regular 101-gon, 2 sin(pi/101) =
# 0.0621997..., and nothing left over; two files are refused.
tr_engine_test(cli_measure_kkt_forces 0 DIR ${_kkt_dir}/forces ONLY "c.vect;f.csv" OUT ${_kkt_dir}/forces/f.csv
  MATCH "\ncomponent,vertex,tension,unresolved,unresolved_x,unresolved_y,unresolved_z\n0,0,6[.]21997[0-9]+e-02,[0-9][.][0-9]+e-1[3-9],"
  CMD sh -c "'${_tr}' make circle --radius 5 --n 101 -o '${_kkt_dir}/forces/c.vect' && exec '${_tr}' measure --kkt-forces '${_kkt_dir}/forces/f.csv' '${_kkt_dir}/forces/c.vect' > /dev/null")
add_test(NAME cli_measure_kkt_forces_two_files COMMAND sh -c
  "'$<TARGET_FILE:tightrope>' measure --kkt-forces '${_kkt_dir}/never.csv' '${CMAKE_CURRENT_SOURCE_DIR}/data/engine_overlap.tsv' '${CMAKE_CURRENT_SOURCE_DIR}/data/engine_overlap.tsv' 2>/dev/null; test $? -eq 2 && test ! -e '${_kkt_dir}/never.csv'")
