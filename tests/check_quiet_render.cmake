# What `glint render` prints (GLINT, PROJECT, OUT a scratch folder): without --verbose, at most
# one progress line (stderr is not a terminal: a line every 5 s, and this render is shorter)
# and the summary, "glint: wrote ..."; with --verbose also the details of the device, the back
# end, the closest hits and the program.
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")

function(render_and_check verbose)
  execute_process(COMMAND "${GLINT}" render "${PROJECT}" -o "${OUT}/out.png" --width 32 --spp 4 ${verbose}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT "${out}" STREQUAL "")
    message(FATAL_ERROR "glint render ${verbose}: exit ${rc}, stdout '${out}'\n${err}")
  endif()
  set(err "${err}" PARENT_SCOPE)
endfunction()

render_and_check("")
string(REGEX REPLACE "\n$" "" text "${err}")
string(REPLACE ";" "," text "${text}")
string(REPLACE "\n" ";" lines "${text}")
set(progress 0)
set(wrote 0)
foreach(line IN LISTS lines)
  if(line MATCHES "^\\[[# ]*\\] ")
    math(EXPR progress "${progress} + 1")
  elseif(line MATCHES "^glint: wrote .*out.png \\(32x[0-9]+, 4 spp, [0-9.]+ s, [0-9.]+ spp/s, [0-9.]+ Msamples/s\\)$")
    math(EXPR wrote "${wrote} + 1")
  else()
    message(FATAL_ERROR "a plain glint render printed a line that is neither progress nor summary: '${line}'\n${err}")
  endif()
endforeach()
if(progress GREATER 1 OR NOT wrote EQUAL 1)
  message(FATAL_ERROR "a plain glint render printed ${progress} progress lines and ${wrote} summaries:\n${err}")
endif()

render_and_check("--verbose")
foreach(detail "glint: OpenGL [^\n]+ on " "glint: trace backend: (fragment|compute) \\(auto"
               "glint: closest hits by " "glint: last pass traced with the (specialised|generic) program"
               "glint: wrote .*out.png \\(32x")
  if(NOT "${err}" MATCHES "${detail}")
    message(FATAL_ERROR "glint render --verbose does not print '${detail}':\n${err}")
  endif()
endforeach()
file(REMOVE_RECURSE "${OUT}")
message(STATUS "glint render: a progress line and the summary; the details with --verbose")
