# One `glint` command line as a user runs it: GLINT (the executable) with ARGS (the arguments,
# separated by "|"), run in the current folder. Checks the exact exit code RC and that stdout
# and stderr together match PATTERN.
include(${CMAKE_CURRENT_LIST_DIR}/expect_exit.cmake)
string(REPLACE "|" ";" args "${ARGS}")
expect_exit("${RC}" "${PATTERN}" "${GLINT}" ${args})
