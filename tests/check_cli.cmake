# One `glint` command line as a user runs it: GLINT (the executable) with ARGS (the arguments,
# separated by "|"), run in the current folder. Checks the exact exit code RC and that stdout
# and stderr together match PATTERN. (ctest's PASS_REGULAR_EXPRESSION ignores the exit code,
# and WILL_FAIL would pass a crash where exit 2 is promised.)
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND "${GLINT}" ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REPLACE ";" " " shown "${args}")
if(NOT "${rc}" STREQUAL "${RC}")
  message(FATAL_ERROR "glint ${shown}: exit ${rc}, expected ${RC}\n${out}${err}")
endif()
if(NOT "${out}${err}" MATCHES "${PATTERN}")
  message(FATAL_ERROR "glint ${shown}: output does not match '${PATTERN}':\n${out}${err}")
endif()
message(STATUS "glint ${shown}: exit ${rc}, output matches '${PATTERN}'")
