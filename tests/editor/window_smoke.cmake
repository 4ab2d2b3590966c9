# editor.window_smoke: the real window under Xvfb renders some frames and writes a screenshot,
# then WindowSmoke.* checks it. Arguments: GLINT, TESTS (glint_editor_tests), PROJECT, OUT.
file(REMOVE "${OUT}")
execute_process(COMMAND xvfb-run -a -s "-screen 0 1280x800x24" "${GLINT}" "${PROJECT}"
                        --screenshot "${OUT}" --frames 60
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0 OR NOT EXISTS "${OUT}")
  message(FATAL_ERROR "glint --screenshot failed (exit ${rc})")
endif()
set(ENV{GLINT_SMOKE_SCREENSHOT} "${OUT}")
execute_process(COMMAND "${TESTS}" --gtest_filter=WindowSmoke.* RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0 OR out MATCHES "SKIPPED")
  message(FATAL_ERROR "the screenshot check failed")
endif()
