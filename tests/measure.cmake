# 'tightrope measure' from the command line (included by tests/CMakeLists.txt).
set(_measure_check ${CMAKE_CURRENT_SOURCE_DIR}/cli/measure_check.cmake)
foreach(mode json array struts dir)
  add_test(NAME cli_measure_${mode}
    COMMAND ${CMAKE_COMMAND} -DTR=$<TARGET_FILE:tightrope> -DMODE=${mode}
            -DSHARED=${TIGHTROPE_SHARED_DIR} -DWORK=${CMAKE_CURRENT_BINARY_DIR}/measure_${mode}
            -P ${_measure_check})
  if(NOT TR_HAVE_SHARED) # they measure the peer table's knots
    set_tests_properties(cli_measure_${mode} PROPERTIES DISABLED TRUE)
  endif()
endforeach()
# Every broken file of the readers' corpus: exit 2, one FILE:LINE line, no --struts file.
file(GLOB _measure_bad CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/bad/*)
foreach(bad ${_measure_bad})
  get_filename_component(_n ${bad} NAME)
  string(MAKE_C_IDENTIFIER ${_n} _id)
  add_test(NAME cli_measure_bad_${_id}
    COMMAND ${CMAKE_COMMAND} -DTR=$<TARGET_FILE:tightrope> -DMODE=bad -DFILE=${bad}
            -DSHARED=${TIGHTROPE_SHARED_DIR} -DWORK=${CMAKE_CURRENT_BINARY_DIR}/measure_bad_${_id}
            -P ${_measure_check})
endforeach()
