# expect_exit(RC PATTERN COMMAND...): runs COMMAND and fails the test unless it exits with
# exactly RC (a crash is not an exit code) and its stdout and stderr together match PATTERN.
# (ctest's PASS_REGULAR_EXPRESSION ignores the exit code, and WILL_FAIL passes a crash.)
function(expect_exit rc_expected pattern)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REPLACE ";" " " shown "${ARGN}")
  if(NOT "${rc}" STREQUAL "${rc_expected}")
    message(FATAL_ERROR "${shown}: exit ${rc}, expected ${rc_expected}\n${out}${err}")
  endif()
  if(NOT "${out}${err}" MATCHES "${pattern}")
    message(FATAL_ERROR "${shown}: output does not match '${pattern}':\n${out}${err}")
  endif()
endfunction()
