# tightrope make: files written in each format, bad arguments refused with one
# line and exit status 2, and a failed write leaves nothing behind.
set(_io_check ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_cli.cmake)
set(_io_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_make)
set(_tr $<TARGET_FILE:tightrope>)

function(tr_io_test name expect)
  cmake_parse_arguments(T "" "DIR;OCCUPY;MATCH;OUT" "CMD;ONLY" ${ARGN})
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DCMD=${T_CMD}" -DEXPECT=${expect} "-DDIR=${T_DIR}"
    "-DONLY=${T_ONLY}" "-DOCCUPY=${T_OCCUPY}" "-DMATCH=${T_MATCH}" "-DOUT=${T_OUT}" -P ${_io_check})
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "${TR_TEST_ENV}")
endfunction()

tr_io_test(make_torus_vect 0 DIR ${_io_dir}/torus ONLY t23.vect OUT ${_io_dir}/torus/t23.vect
  MATCH "^VECT\n# torus knot T\\(2,3\\)[^\n]*\n# length [0-9.]+\n[^\n]*\n1 200 0 [^\n]*\n-200 "
  CMD ${_tr} make torus 2 3 --n 200 -o ${_io_dir}/torus/t23.vect)
tr_io_test(make_hopf_tsv 0 DIR ${_io_dir}/hopf ONLY hopf.tsv OUT ${_io_dir}/hopf/hopf.tsv
  MATCH "^# hopf link[^\n]*\n# length [^\n]*\n# made by[^\n]*\n3\t0\t0\n"
  CMD ${_tr} make hopf --n 40 -o ${_io_dir}/hopf/hopf.tsv)
tr_io_test(make_circle_txt 0 DIR ${_io_dir}/circle ONLY c.txt OUT ${_io_dir}/circle/c.txt
  MATCH "^# circle of radius 2,[^\n]*\n[^\n]*\n[^\n]*\n2\t0\t0\n"
  CMD ${_tr} make circle --radius 2 --n 13 -o ${_io_dir}/circle/c.txt)
tr_io_test(make_clasp_vect 0 DIR ${_io_dir}/clasp ONLY clasp.vect OUT ${_io_dir}/clasp/clasp.vect
  MATCH "\n2 120 0 [^\n]*\n60 60 [^\n]*\n0 0 [^\n]*\n# Constraint 1 Plane 0 0 1 6\n# Constraint 2 Plane 0 0 1 -6\n"
  CMD ${_tr} make clasp --n 60 --height 6 -o ${_io_dir}/clasp/clasp.vect)
tr_io_test(make_help 0 CMD ${_tr} make --help)

# refused: nothing may be written
tr_io_test(make_no_dir 2 CMD ${_tr} make circle -o ${_io_dir}/no/such/dir/c.vect)
tr_io_test(make_target_occupied 2 DIR ${_io_dir}/occupied OCCUPY ${_io_dir}/occupied/c.vect ONLY c.vect
  CMD ${_tr} make circle -o ${_io_dir}/occupied/c.vect)
tr_io_test(make_open_to_tsv 2 DIR ${_io_dir}/open ONLY ""
  CMD ${_tr} make clasp -o ${_io_dir}/open/clasp.tsv)
tr_io_test(make_not_coprime 2 DIR ${_io_dir}/coprime ONLY ""
  CMD ${_tr} make torus 2 4 -o ${_io_dir}/coprime/t.vect)
tr_io_test(make_too_coarse 2 DIR ${_io_dir}/coarse ONLY ""
  CMD ${_tr} make torus 2 3 --n 10 -o ${_io_dir}/coarse/t.vect)
tr_io_test(make_bad_n 2 CMD ${_tr} make circle --n ten -o x.vect)
tr_io_test(make_no_output 2 CMD ${_tr} make circle)
tr_io_test(make_unknown_kind 2 CMD ${_tr} make trefoil -o x.vect)
tr_io_test(make_unknown_ext 2 CMD ${_tr} make circle -o x.obj)
tr_io_test(make_unknown_option 2 CMD ${_tr} make circle --frobnicate -o x.vect)
tr_io_test(make_no_kind 2 CMD ${_tr} make)
