# Runs one tightrope command and checks that its standard output is one JSON
# document (CMake's own parser, independent of ours), that MEMBER (a
# ;-path, e.g. results;0;contacts_s) is there, and that its type is TYPE
# (NULL, NUMBER, STRING, ...). Variables (-D): CMD (a ;-list), MEMBER, TYPE.
cmake_minimum_required(VERSION 3.19)
execute_process(COMMAND ${CMD} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "exit status ${rc}\nstderr: ${err}")
endif()
string(JSON type ERROR_VARIABLE jerr TYPE "${out}" ${MEMBER})
if(jerr)
  message(FATAL_ERROR "not JSON with member '${MEMBER}': ${jerr}\nstdout: ${out}")
endif()
if(NOT type STREQUAL TYPE)
  message(FATAL_ERROR "member '${MEMBER}' is ${type}, want ${TYPE}\nstdout: ${out}")
endif()
message(STATUS "${MEMBER}: ${type}")
