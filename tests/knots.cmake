# Knots by name, braid word and PD code (issue 47; included by
# tests/CMakeLists.txt; label cli): make knot/link writes a start whose type
# it checked, measure --identify holds a curve against a name; bad notation
# and unknown names are refused with one line, exit 2, nothing written. The
# in-process loop over every name to 10 crossings (and links to 9) is
# tests/tighten/test_knot_starts.c; the tables themselves tests/topology/test_knot_table.c.
set(_kn_check ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_cli.cmake)
set(_kn_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_knots)
set(_tr $<TARGET_FILE:tightrope>)
function(tr_knot_test name expect)
  cmake_parse_arguments(T "" "DIR;MATCH;OUT;ERRMATCH" "CMD;ONLY" ${ARGN})
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DCMD=${T_CMD}" -DEXPECT=${expect} "-DDIR=${T_DIR}"
    "-DONLY=${T_ONLY}" "-DMATCH=${T_MATCH}" "-DOUT=${T_OUT}" "-DERRMATCH=${T_ERRMATCH}" -P ${_kn_check})
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
endfunction()

# by name, in KnotInfo's and Rolfsen's spellings; the file says what was checked
tr_knot_test(make_knot_name 0 DIR ${_kn_dir}/name ONLY "k.vect" OUT ${_kn_dir}/name/k.vect
  MATCH "knot 7_4 [(]KnotInfo[)][^\n]*\n# type checked: Alexander polynomial 4 -7 4, determinant 15, signature -2, as 7_4's\n"
  CMD ${_tr} make knot 7.4 -o ${_kn_dir}/name/k.vect)
# a knot's name makes its minimal diagram (KnotInfo's PD code) and its braid's closure, both
# relaxed (geometry/relax.h), and keeps the shorter (9_8: the diagram, 129.1 against 183.5 at
# thickness 1.25; 9_1, the (2, 9) torus knot: the closure, 105.2 against 108.3); a link's name its
# braid's closure relaxed; the braid's closure as drawn on request; the type is checked either way
tr_knot_test(make_knot_relaxed 0 DIR ${_kn_dir}/relaxed ONLY "k.vect" OUT ${_kn_dir}/relaxed/k.vect
  MATCH "knot 9_8 [(]KnotInfo[)], its minimal diagram [(]KnotInfo's PD code[)], relaxed [(]shorter than its braid's closure relaxed: [0-9.]+ against [0-9.]+[)], [^\n]*\n# type checked: [^\n]*as 9_8's\n"
  CMD ${_tr} make knot 9_8 -o ${_kn_dir}/relaxed/k.vect)
tr_knot_test(make_knot_braid_shorter 0 DIR ${_kn_dir}/braid_shorter ONLY "k.vect" OUT ${_kn_dir}/braid_shorter/k.vect
  MATCH "knot 9_1 [(]KnotInfo[)], closure of its 2-strand braid, relaxed [(]shorter than its minimal diagram relaxed: [0-9.]+ against [0-9.]+[)], [^\n]*\n# type checked: [^\n]*as 9_1's\n"
  CMD ${_tr} make knot 9_1 -o ${_kn_dir}/braid_shorter/k.vect)
tr_knot_test(make_link_relaxed 0 DIR ${_kn_dir}/link_relaxed ONLY "l.vect" OUT ${_kn_dir}/link_relaxed/l.vect
  MATCH "link L4a1[{]1[}] [(]LinkInfo[)], closure of its [0-9]-strand braid, relaxed, [^\n]*\n# type checked: [^\n]*as L4a1[{]1[}]'s\n"
  CMD ${_tr} make link L4a1{1} -o ${_kn_dir}/link_relaxed/l.vect)
tr_knot_test(make_knot_as_drawn 0 DIR ${_kn_dir}/drawn ONLY "k.vect" OUT ${_kn_dir}/drawn/k.vect
  MATCH "knot 9_8 [(]KnotInfo[)], closure of its 5-strand braid, 2485 vertices[^\n]*\n# type checked: [^\n]*as 9_8's\n"
  CMD ${_tr} make knot 9_8 --as-drawn -o ${_kn_dir}/drawn/k.vect)
tr_knot_test(make_torus_as_drawn 2 DIR ${_kn_dir}/torus_drawn ONLY ""
  ERRMATCH "--as-drawn is an option of make knot and make link"
  CMD ${_tr} make torus 2 3 --as-drawn -o ${_kn_dir}/torus_drawn/t.vect)
tr_knot_test(make_knot_unknot 0 DIR ${_kn_dir}/unknot ONLY "k.vect" OUT ${_kn_dir}/unknot/k.vect
  MATCH "type checked: Alexander polynomial 1, determinant 1, signature 0, as 0_1's"
  CMD ${_tr} make knot 0_1 -o ${_kn_dir}/unknot/k.vect)
tr_knot_test(make_knot_12 0 DIR ${_kn_dir}/k12 ONLY "k.vect" OUT ${_kn_dir}/k12/k.vect
  MATCH "as 12n_888's"
  CMD ${_tr} make knot 12n888 -o ${_kn_dir}/k12/k.vect)
tr_knot_test(make_link_name 0 DIR ${_kn_dir}/link ONLY "l.vect" OUT ${_kn_dir}/link/l.vect
  MATCH "type checked: 3 components, linking numbers 0 0 0, components' determinants and signatures 1/0 1/0 1/0, as L6a4[{]0,0[}]'s"
  CMD ${_tr} make link L6a4 -o ${_kn_dir}/link/l.vect)
# an unknown name: the nearest suggested
tr_knot_test(make_knot_unknown 2 DIR ${_kn_dir}/unknown ONLY ""
  ERRMATCH "no knot named '3_l' in the table [^\n]*; nearest: 3_1"
  CMD ${_tr} make knot 3_l -o ${_kn_dir}/unknown/k.vect)
tr_knot_test(make_knot_is_link 2 DIR ${_kn_dir}/islink ONLY ""
  ERRMATCH "L2a1[{]0[}] is a link, not a knot [(]tightrope make link"
  CMD ${_tr} make knot L2a1 -o ${_kn_dir}/islink/k.vect)
# bad notation
tr_knot_test(make_knot_braid_empty 2 DIR ${_kn_dir}/bempty ONLY "" ERRMATCH "braid word: empty"
  CMD ${_tr} make knot --braid "[ ]" -o ${_kn_dir}/bempty/k.vect)
tr_knot_test(make_knot_braid_zero 2 DIR ${_kn_dir}/bzero ONLY "" ERRMATCH "generator 3 is 0"
  CMD ${_tr} make knot --braid "1,-2,0,-2" -o ${_kn_dir}/bzero/k.vect)
tr_knot_test(make_knot_braid_link 2 DIR ${_kn_dir}/blink ONLY "" ERRMATCH "closure has 2 components, not one [(]a link: tightrope make link --braid[)]"
  CMD ${_tr} make knot --braid "1,1" -o ${_kn_dir}/blink/k.vect)
tr_knot_test(make_knot_pd_label 2 DIR ${_kn_dir}/pdlabel ONLY "" ERRMATCH "label 5 appears 3 times, not twice"
  CMD ${_tr} make knot --pd "[[1,5,2,4],[3,1,4,6],[5,3,5,2]]" -o ${_kn_dir}/pdlabel/k.vect)
tr_knot_test(make_knot_pd_link 2 DIR ${_kn_dir}/pdlink ONLY "" ERRMATCH "--pd makes knots only"
  CMD ${_tr} make link --pd "[[1,5,2,4],[3,1,4,6],[5,3,6,2]]" -o ${_kn_dir}/pdlink/k.vect)
# any diagram a user writes: a braid word, the trefoil's PD code
tr_knot_test(make_knot_pd_trefoil 0 DIR ${_kn_dir}/pd ONLY "k.vect;id.txt" OUT ${_kn_dir}/pd/id.txt
  MATCH "identify 3_1: match"
  CMD sh -c "'${_tr}' make knot --pd 'X[1,5,2,4] X[3,1,4,6] X[5,3,6,2]' -o '${_kn_dir}/pd/k.vect' >/dev/null && exec '${_tr}' measure '${_kn_dir}/pd/k.vect' --identify 3_1 > '${_kn_dir}/pd/id.txt'")
# the type checked, never assumed: a wrong name fails (exit 1, one line)
tr_knot_test(identify_wrong 1 DIR ${_kn_dir}/wrong ONLY "k.vect"
  ERRMATCH "k[.]vect is not 4_1: Alexander polynomial 1 -1 1, 4_1's is -1 3 -1"
  CMD sh -c "'${_tr}' make knot 3_1 -o '${_kn_dir}/wrong/k.vect' >/dev/null && exec '${_tr}' measure '${_kn_dir}/wrong/k.vect' --identify 4_1")
tr_knot_test(identify_braid_not_name 1 DIR ${_kn_dir}/notname ONLY "k.vect"
  ERRMATCH "is not 3_1: Alexander polynomial -1 3 -1"
  CMD sh -c "'${_tr}' make knot --braid '1,-2,1,-2' -o '${_kn_dir}/notname/k.vect' >/dev/null && exec '${_tr}' measure '${_kn_dir}/notname/k.vect' --identify 3_1")
# without a name: the candidates, ambiguity stated (6_1 and 9_46 share them)
tr_knot_test(identify_candidates 0 DIR ${_kn_dir}/cand ONLY "k.vect;id.txt" OUT ${_kn_dir}/cand/id.txt
  MATCH "\ncandidates: 6_1 9_46 11n_67 [^\n]*[(]9 of the table's knots"
  CMD sh -c "'${_tr}' make knot 6_1 -o '${_kn_dir}/cand/k.vect' >/dev/null && exec '${_tr}' measure --identify '${_kn_dir}/cand/k.vect' > '${_kn_dir}/cand/id.txt'")
tr_knot_test(identify_link 0 DIR ${_kn_dir}/lid ONLY "l.vect;id.txt" OUT ${_kn_dir}/lid/id.txt
  MATCH "identify L4a1[{]1[}]: match"
  CMD sh -c "'${_tr}' make link L4a1{1} -o '${_kn_dir}/lid/l.vect' >/dev/null && exec '${_tr}' measure '${_kn_dir}/lid/l.vect' --identify L4a1{1} > '${_kn_dir}/lid/id.txt'")
tr_knot_test(identify_unknown_name 2 DIR ${_kn_dir}/idunk ONLY "k.vect" ERRMATCH "no knot or link named '4_2'"
  CMD sh -c "'${_tr}' make knot 4_1 -o '${_kn_dir}/idunk/k.vect' >/dev/null && exec '${_tr}' measure '${_kn_dir}/idunk/k.vect' --identify 4_2")
# a name stands for a knot and its mirror image; the signature tells which
tr_knot_test(identify_mirror 0 DIR ${_kn_dir}/mirror ONLY "k.vect;id.txt" OUT ${_kn_dir}/mirror/id.txt
  MATCH "signature 2\nidentify 3_1: match [(][^\n]*the mirror image of KnotInfo's diagram[)]"
  CMD sh -c "'${_tr}' make knot --braid '-1,-1,-1' -o '${_kn_dir}/mirror/k.vect' >/dev/null && exec '${_tr}' measure '${_kn_dir}/mirror/k.vect' --identify 3_1 > '${_kn_dir}/mirror/id.txt'")
# 5_1 and 10_132 share Alexander polynomial and determinant; the signature
# (-4 and 0) tells them apart
tr_knot_test(identify_signature 1 DIR ${_kn_dir}/sig ONLY "k.vect"
  ERRMATCH "is not 5_1: signature 0, 5_1's is -4"
  CMD sh -c "'${_tr}' make knot 10_132 -o '${_kn_dir}/sig/k.vect' >/dev/null && exec '${_tr}' measure '${_kn_dir}/sig/k.vect' --identify 5_1")
