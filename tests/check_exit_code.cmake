# Runs COMMAND (a ;-list) and checks its exact exit code and that its stderr matches a regex.
# Arguments: COMMAND, EXPECTED_CODE, EXPECTED_STDERR.
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${err}")
if(NOT rc STREQUAL "${EXPECTED_CODE}")
  message(FATAL_ERROR "exit ${rc}, expected ${EXPECTED_CODE}")
endif()
if(NOT err MATCHES "${EXPECTED_STDERR}")
  message(FATAL_ERROR "stderr does not match '${EXPECTED_STDERR}'")
endif()
