# libFuzzer target for the curve readers, built with clang (the project
# compiler is gcc, so it is a custom command over the few sources it needs)
# and run by a test for a bounded time. Only with TIGHTROPE_FUZZ=ON and a
# clang whose libFuzzer links; otherwise no fuzz test is registered.
if(TIGHTROPE_FUZZ)
  find_program(TR_FUZZ_CLANG NAMES clang-14 clang)
  set(_fz_ok FALSE)
  if(TR_FUZZ_CLANG)
    set(_fz_probe ${CMAKE_CURRENT_BINARY_DIR}/fuzz_probe.c)
    file(WRITE ${_fz_probe} "#include <stddef.h>\n#include <stdint.h>\nint LLVMFuzzerTestOneInput(const uint8_t *d, size_t n);\nint LLVMFuzzerTestOneInput(const uint8_t *d, size_t n) { (void)d; (void)n; return 0; }\n")
    execute_process(COMMAND ${TR_FUZZ_CLANG} -fsanitize=fuzzer,address,undefined ${_fz_probe}
                            -o ${CMAKE_CURRENT_BINARY_DIR}/fuzz_probe
                    RESULT_VARIABLE _fz_rc OUTPUT_QUIET ERROR_QUIET)
    if(_fz_rc EQUAL 0)
      set(_fz_ok TRUE)
    endif()
  endif()
  if(_fz_ok)
    set(_fz_sources ${CMAKE_SOURCE_DIR}/tests/curve/fuzz_readers.c
                    ${CMAKE_SOURCE_DIR}/host/curve/curve_io.c ${CMAKE_SOURCE_DIR}/host/curve/vect.c
                    ${CMAKE_SOURCE_DIR}/host/curve/point_list.c ${CMAKE_SOURCE_DIR}/host/curve/curve.c
                    ${CMAKE_SOURCE_DIR}/host/util/error.c ${CMAKE_SOURCE_DIR}/host/util/text_file.c)
    set(_fz_bin ${CMAKE_CURRENT_BINARY_DIR}/fuzz_readers)
    add_custom_command(OUTPUT ${_fz_bin}
      COMMAND ${TR_FUZZ_CLANG} -std=c17 -D_POSIX_C_SOURCE=200809L -g -O1 -Wall -Wextra -Werror
              -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
              -I${CMAKE_SOURCE_DIR}/host ${_fz_sources} -lm -o ${_fz_bin}
      DEPENDS ${_fz_sources} ${CMAKE_SOURCE_DIR}/host/curve/curve_io.h ${CMAKE_SOURCE_DIR}/host/curve/curve_io_formats.h
              ${CMAKE_SOURCE_DIR}/host/curve/curve.h ${CMAKE_SOURCE_DIR}/host/util/error.h
              ${CMAKE_SOURCE_DIR}/host/util/text_file.h ${CMAKE_SOURCE_DIR}/host/util/vec3.h
      COMMENT "Building the libFuzzer target fuzz_readers with clang")
    add_custom_target(fuzz_readers ALL DEPENDS ${_fz_bin})
    # New inputs go to the first corpus directory, which lives in the build
    # tree; the broken-file corpus and the KnotPlot files are read-only seeds.
    set(_fz_corpus ${CMAKE_CURRENT_BINARY_DIR}/fuzz_corpus)
    file(MAKE_DIRECTORY ${_fz_corpus})
    set(_fz_seeds ${CMAKE_SOURCE_DIR}/tests/bad)
    if(TR_HAVE_SHARED)
      list(APPEND _fz_seeds ${TIGHTROPE_SHARED_DIR}/data/knotplot)
    else()
      list(APPEND _fz_seeds ${CMAKE_SOURCE_DIR}/tests/data/knotplot)
    endif()
    add_test(NAME fuzz_readers
      COMMAND ${_fz_bin} -max_total_time=20 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
              -artifact_prefix=${CMAKE_CURRENT_BINARY_DIR}/fuzz-
              ${_fz_corpus} ${_fz_seeds})
    set_tests_properties(fuzz_readers PROPERTIES LABELS "curve;fuzz" TIMEOUT 120
      ENVIRONMENT "ASAN_OPTIONS=detect_leaks=1;UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")
  else()
    message(STATUS "TIGHTROPE_FUZZ: no clang with libFuzzer found, fuzz test not registered")
  endif()
endif()
