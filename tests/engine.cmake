# tightrope tighten: bad options and impossible starts are refused with one
# line and exit status 2 (nothing written); a short run writes a certified
# curve; --json prints the summary; a checkpoint can be resumed.
set(_eng_check ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_cli.cmake)
set(_eng_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_tighten)
set(_tr $<TARGET_FILE:tightrope>)

function(tr_engine_test name expect)
  cmake_parse_arguments(T "" "DIR;MATCH;OUT;ERRMATCH" "CMD;ONLY" ${ARGN})
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} "-DCMD=${T_CMD}" -DEXPECT=${expect} "-DDIR=${T_DIR}"
    "-DONLY=${T_ONLY}" "-DMATCH=${T_MATCH}" "-DOUT=${T_OUT}" "-DERRMATCH=${T_ERRMATCH}" -P ${_eng_check})
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "${TR_TEST_ENV}")
endfunction()

tr_engine_test(tighten_help 0 CMD ${_tr} tighten --help)
tr_engine_test(tighten_no_input 2 CMD ${_tr} tighten -o ${_eng_dir}/x.vect)
tr_engine_test(tighten_no_output 2 CMD ${_tr} tighten ${CMAKE_CURRENT_SOURCE_DIR}/data/engine_overlap.tsv)
tr_engine_test(tighten_bad_option 2 DIR ${_eng_dir}/badopt ONLY ""
  CMD ${_tr} tighten ${CMAKE_CURRENT_SOURCE_DIR}/data/engine_overlap.tsv -o ${_eng_dir}/badopt/x.vect --bogus)
tr_engine_test(tighten_bad_steps 2 DIR ${_eng_dir}/badsteps ONLY ""
  CMD ${_tr} tighten ${CMAKE_CURRENT_SOURCE_DIR}/data/engine_overlap.tsv -o ${_eng_dir}/badsteps/x.vect --steps many)
tr_engine_test(tighten_bad_time 2 DIR ${_eng_dir}/badtime ONLY ""
  CMD ${_tr} tighten ${CMAKE_CURRENT_SOURCE_DIR}/data/engine_overlap.tsv -o ${_eng_dir}/badtime/x.vect --time-limit -3)
tr_engine_test(tighten_missing_file 2 DIR ${_eng_dir}/missing ONLY ""
  CMD ${_tr} tighten ${_eng_dir}/missing/none.vect -o ${_eng_dir}/missing/x.vect)
tr_engine_test(tighten_overlapping_start 2 DIR ${_eng_dir}/overlap ONLY ""
  CMD ${_tr} tighten ${CMAKE_CURRENT_SOURCE_DIR}/data/engine_overlap.tsv -o ${_eng_dir}/overlap/x.vect)
tr_engine_test(tighten_too_coarse 2 DIR ${_eng_dir}/coarse ONLY ""
  CMD ${_tr} tighten ${CMAKE_CURRENT_SOURCE_DIR}/data/circle_r3_n12.txt -o ${_eng_dir}/coarse/x.vect)
tr_engine_test(tighten_bad_device 2 DIR ${_eng_dir}/dev ONLY "s.vect"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_eng_dir}/dev/s.vect' && exec '${_tr}' tighten '${_eng_dir}/dev/s.vect' -o '${_eng_dir}/dev/x.vect' --device no-such-device-xyz")
# --device opencl where no OpenCL platform is installed (ocl-icd reads its
# vendors from OCL_ICD_VENDORS): the reason, not "unknown device", and exit 1
# (the device failed; no fallback to the reference for an explicit choice)
tr_engine_test(tighten_opencl_absent 1 DIR ${_eng_dir}/noicd ONLY "s.vect"
  ERRMATCH "^tightrope tighten: device 'opencl': no usable opencl device"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_eng_dir}/noicd/s.vect' && OCL_ICD_VENDORS='${_eng_dir}/noicd/none' exec '${_tr}' tighten '${_eng_dir}/noicd/s.vect' -o '${_eng_dir}/noicd/x.vect' --device opencl")
# "serial" names the reference, as in tr_device_select
tr_engine_test(tighten_device_serial 0 DIR ${_eng_dir}/serial ONLY "s.vect;t.vect"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_eng_dir}/serial/s.vect' && exec '${_tr}' tighten '${_eng_dir}/serial/s.vect' -o '${_eng_dir}/serial/t.vect' --steps 2 --quiet --device serial")
# The output's format and both paths are checked before the run, so a long
# run cannot end in "cannot write" (--time-limit 600 would show as a timeout).
tr_engine_test(tighten_output_dir_missing 2 DIR ${_eng_dir}/outmiss ONLY "s.vect"
  ERRMATCH "cannot write .*/nodir/x.vect"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_eng_dir}/outmiss/s.vect' && exec '${_tr}' tighten '${_eng_dir}/outmiss/s.vect' -o '${_eng_dir}/outmiss/nodir/x.vect' --time-limit 600")
tr_engine_test(tighten_output_format 2 DIR ${_eng_dir}/outfmt ONLY "h.vect"
  ERRMATCH "not writing .*h.txt: a knotplot list holds one component"
  CMD sh -c "'${_tr}' make hopf --n 64 -o '${_eng_dir}/outfmt/h.vect' && exec '${_tr}' tighten '${_eng_dir}/outfmt/h.vect' -o '${_eng_dir}/outfmt/h.txt' --time-limit 600")
tr_engine_test(tighten_checkpoint_dir_missing 2 DIR ${_eng_dir}/ckmiss ONLY "s.vect"
  ERRMATCH "cannot write .*/nodir/ck"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_eng_dir}/ckmiss/s.vect' && exec '${_tr}' tighten '${_eng_dir}/ckmiss/s.vect' -o '${_eng_dir}/ckmiss/x.vect' --checkpoint '${_eng_dir}/ckmiss/nodir/ck' --time-limit 600")
# a checkpoint over the input would destroy the start curve
tr_engine_test(tighten_checkpoint_is_input 2 DIR ${_eng_dir}/ckin ONLY "s.vect"
  ERRMATCH "--checkpoint .*s.vect is the input file"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_eng_dir}/ckin/s.vect' && exec '${_tr}' tighten '${_eng_dir}/ckin/s.vect' -o '${_eng_dir}/ckin/x.vect' --checkpoint '${_eng_dir}/ckin/./s.vect' --steps 2")
tr_engine_test(tighten_resume_with_input 2 CMD ${_tr} tighten --resume ${_eng_dir}/none.ck ${_eng_dir}/none.vect -o ${_eng_dir}/x.vect
  ERRMATCH "--resume continues the checkpoint's curve")
# --n above the file's count adds vertices along a spline, not on the old
# edges: a smooth 150-vertex trefoil taken to 1000 keeps MinRad near 1.7
# (on the edges it fell to 0.43 and the start was refused)
tr_engine_test(tighten_upsample 0 DIR ${_eng_dir}/up ONLY "s.vect;t.vect" OUT ${_eng_dir}/up/t.vect
  MATCH "\n# N 1000\n# length [0-9.]+\n# MinRad 1[.][5-9]"
  CMD sh -c "'${_tr}' make torus 2 3 --n 150 -o '${_eng_dir}/up/s.vect' && exec '${_tr}' tighten '${_eng_dir}/up/s.vect' -o '${_eng_dir}/up/t.vect' --n 1000 --steps 1 --quiet --no-kkt --device reference")
# --scale: a regular 64-gon of circumradius 1/2 (thickness = Rawdon's MinRad
# r cos(pi/n) < 1, refused as it is) scaled to thickness 1 has ropelength
# 2n tan(pi/n) = 6.28824 (a circle cannot get shorter)
tr_engine_test(tighten_scale 0 DIR ${_eng_dir}/scale ONLY "t.vect" OUT ${_eng_dir}/scale/t.vect
  MATCH "\n# N 64\n# length 6[.]2882[34][0-9]*\n"
  CMD ${_tr} tighten ${CMAKE_CURRENT_SOURCE_DIR}/data/circle_r0.5_n64.txt -o ${_eng_dir}/scale/t.vect --scale --steps 1 --quiet --no-kkt --device reference)
# --scale on a clasp scales its end planes with it; a start too coarse at
# thickness 1 is resampled, not refused (tests/scripts/scale_cli.sh)
foreach(c clasp coarse)
  add_test(NAME tighten_scale_${c}
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/scale_cli.sh ${c} $<TARGET_FILE:tightrope> ${_eng_dir}/scale_${c})
  set_tests_properties(tighten_scale_${c} PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
endforeach()
tr_engine_test(tighten_trefoil_steps 0 DIR ${_eng_dir}/trefoil ONLY "s.vect;t.vect" OUT ${_eng_dir}/trefoil/t.vect
  MATCH "^VECT\n# tightened by tightrope[^\n]*\n# command: tighten [^\n]*--steps 20[^\n]*\n# N 72\n# length [0-9.]+\n# MinRad [0-9.]+\n# dcsd [0-9.]+\n# thickness (1|0[.]99999999)[0-9.]*\n# ropelength [0-9.]+\n# residual [^\n]+\n# steps 20\n# stop steps\n"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_eng_dir}/trefoil/s.vect' && exec '${_tr}' tighten '${_eng_dir}/trefoil/s.vect' -o '${_eng_dir}/trefoil/t.vect' --steps 20 --quiet")
# a requested ropelength that a 5-step run cannot reach: best state written, exit 1
tr_engine_test(tighten_target_not_reached 1 DIR ${_eng_dir}/target ONLY "s.vect;t.vect" OUT ${_eng_dir}/target/t.vect
  MATCH "^VECT\n# tightened by tightrope[^\n]*\n# command: tighten [^\n]*--target 20[^\n]*\n# N 72\n"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_eng_dir}/target/s.vect' && exec '${_tr}' tighten '${_eng_dir}/target/s.vect' -o '${_eng_dir}/target/t.vect' --steps 5 --target 20 --quiet --device reference")
tr_engine_test(tighten_json_resume 0 DIR ${_eng_dir}/resume ONLY "s.vect;t.vect;u.vect;ck.txt;json.txt" OUT ${_eng_dir}/resume/json.txt
  MATCH "^{\n  \"output\": [^\n]*\n  \"device\": \"serial reference[^\n]*\n  \"stop\": \"steps\",\n  \"N\": 72,\n  \"steps\": 16,\n"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_eng_dir}/resume/s.vect' && '${_tr}' tighten '${_eng_dir}/resume/s.vect' -o '${_eng_dir}/resume/t.vect' --steps 8 --checkpoint '${_eng_dir}/resume/ck.txt' --quiet --device reference > /dev/null && exec '${_tr}' tighten --resume '${_eng_dir}/resume/ck.txt' -o '${_eng_dir}/resume/u.vect' --steps 16 --json --device reference > '${_eng_dir}/resume/json.txt'")
# a resumed run checks its result's knot type against the checkpoint's state
# (the (2,3) torus knot: the trefoil's Alexander polynomial and determinant)
tr_engine_test(tighten_resume_type 0 DIR ${_eng_dir}/resumetype ONLY "s.vect;t.vect;u.vect;ck.txt" OUT ${_eng_dir}/resumetype/u.vect
  MATCH "\n# knot type kept: Alexander polynomial 1 -1 1, determinant 3, signature -?2 [(]the start's[)]\n"
  CMD sh -c "'${_tr}' make torus 2 3 --n 72 -o '${_eng_dir}/resumetype/s.vect' && '${_tr}' tighten '${_eng_dir}/resumetype/s.vect' -o '${_eng_dir}/resumetype/t.vect' --steps 8 --checkpoint '${_eng_dir}/resumetype/ck.txt' --quiet --device reference && exec '${_tr}' tighten --resume '${_eng_dir}/resumetype/ck.txt' -o '${_eng_dir}/resumetype/u.vect' --steps 16 --quiet --device reference")
# --residual is met by the certificate of the output when the engine jams:
# the 2 x 40 clasp jams with the engine's own residual near 0.3 and a KKT
# residual near 1e-4 after polish; asked for 1e-3 it exits 0 and says so.
tr_engine_test(tighten_residual_kkt 0 DIR ${_eng_dir}/reskkt ONLY "c.vect;t.vect" OUT ${_eng_dir}/reskkt/t.vect
  MATCH "\n# stop jammed\n# knot type not checked [(]the start: component 0 is open[)]\n# kkt_residual [0-9][.][0-9]+e-0[4-9] "
  CMD sh -c "'${_tr}' make clasp --n 40 -o '${_eng_dir}/reskkt/c.vect' && exec '${_tr}' tighten '${_eng_dir}/reskkt/c.vect' -o '${_eng_dir}/reskkt/t.vect' --residual 1e-3 --quiet --device reference")
# Coarse levels below --device-from run on the serial reference, the final
# level on the chosen device (tests/scripts/device_levels.sh; skipped
# without an OpenCL device).
add_test(NAME tighten_device_levels
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/device_levels.sh $<TARGET_FILE:tightrope>
          ${CMAKE_CURRENT_BINARY_DIR}/cli_tighten/device_levels)
set_tests_properties(tighten_device_levels PROPERTIES SKIP_RETURN_CODE 77 ENVIRONMENT "${TR_TEST_ENV}")
# a checkpoint that cannot be written is a warning (tests/scripts/checkpoint_cli.sh)
add_test(NAME tighten_checkpoint_vanished
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/checkpoint_cli.sh $<TARGET_FILE:tightrope> ${_eng_dir}/ckpt_vanished)
set_tests_properties(tighten_checkpoint_vanished PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
# the second-order solver checkpoints; --resume goes on from it (tests/scripts/solver_checkpoint.sh)
add_test(NAME tighten_solver_checkpoint
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/solver_checkpoint.sh $<TARGET_FILE:tightrope>
          ${PROJECT_SOURCE_DIR}/bench/data/trefoil_2400.vect ${_eng_dir}/solver_ckpt)
set_tests_properties(tighten_solver_checkpoint PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
# a tighten stopped mid-solve resumes the solve's state and takes the steps
# it had left (tests/scripts/solver_state_resume.sh; host/engine/solver_state.c)
add_test(NAME tighten_solver_state_resume
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/solver_state_resume.sh $<TARGET_FILE:tightrope>
          ${PROJECT_SOURCE_DIR}/bench/data/trefoil_2400.vect ${_eng_dir}/solver_state_resume)
set_tests_properties(tighten_solver_state_resume PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
# --tries K --seed S: the shortest of K roads, reproducible (tests/scripts/tries_cli.sh)
add_test(NAME tighten_tries
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/tries_cli.sh $<TARGET_FILE:tightrope> ${_eng_dir}/tries)
set_tests_properties(tighten_tries PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
# The automatic roads of a plain tighten with a time limit (tests/scripts/auto_roads_cli.sh)
add_test(NAME tighten_auto_roads
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/auto_roads_cli.sh $<TARGET_FILE:tightrope> ${_eng_dir}/auto_roads)
set_tests_properties(tighten_auto_roads PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
# A result longer than its start is said on stderr (tests/scripts/longer_than_start_cli.sh)
add_test(NAME tighten_longer_than_start
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/longer_than_start_cli.sh $<TARGET_FILE:tightrope> ${_eng_dir}/longer)
set_tests_properties(tighten_longer_than_start PROPERTIES ENVIRONMENT "${TR_TEST_ENV}" LABELS cli)
