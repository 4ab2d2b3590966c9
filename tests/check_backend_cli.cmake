# `glint render --backend` (GLINT, PROJECT, OUT a scratch folder): fragment and compute render
# and say so, auto times once and then reads its cache (in OUT, never the user's ~/.cache), and
# bad values exit 2 with a message naming the option. The back end is a detail: --verbose.
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")

include(${CMAKE_CURRENT_LIST_DIR}/expect_exit.cmake)
function(expect args rc_expected pattern)
  expect_exit("${rc_expected}" "${pattern}" ${CMAKE_COMMAND} -E env XDG_CACHE_HOME=${OUT}/cache
              "${GLINT}" render "${PROJECT}" -o "${OUT}/out.png" --width 24 --spp 2 --verbose ${args})
endfunction()

expect("--backend;fragment" 0 "trace backend: fragment \\(--backend\\)")
expect("--backend;compute" 0 "trace backend: compute \\(--backend\\)")
expect("--backend;compute;--work-group;16x4" 0 "wrote .*out.png \\(24x")
if(EXISTS "${OUT}/cache/glint/backend.json")
  message(FATAL_ERROR "a forced --backend wrote the backend cache")
endif()
expect("--backend;auto" 0 "trace backend: (fragment|compute) \\(auto, timed now")
if(NOT EXISTS "${OUT}/cache/glint/backend.json")
  message(FATAL_ERROR "--backend auto did not write ${OUT}/cache/glint/backend.json")
endif()
expect("" 0 "trace backend: (fragment|compute) \\(auto, cached")
# 24 px wide: on llvmpipe with more than one thread, one tile for several threads, so the
# automatic choice renders with the compute shader and says why.
execute_process(COMMAND ${CMAKE_COMMAND} -E env XDG_CACHE_HOME=${OUT}/cache "${GLINT}" render "${PROJECT}"
                -o "${OUT}/out.png" --width 24 --spp 2 --verbose OUTPUT_VARIABLE out ERROR_VARIABLE err)
cmake_host_system_information(RESULT cpus QUERY NUMBER_OF_LOGICAL_CORES)
if("${err}" MATCHES " on llvmpipe" AND cpus GREATER 1)
  if(NOT "${err}" MATCHES "trace backend: compute \\(auto, cached")
    message(FATAL_ERROR "a 24-pixel image on llvmpipe did not take the compute shader:\n${err}")
  endif()
  # Unless the device's own (timed) choice was compute already, the line says why.
  string(REGEX MATCH "fragment ([0-9]+) spp/s, compute ([0-9]+) spp/s" rates "${err}")
  math(EXPR compute_x10 "${CMAKE_MATCH_2} * 10")
  math(EXPR fragment_x11 "${CMAKE_MATCH_1} * 11")
  if(NOT compute_x10 GREATER fragment_x11 AND
     NOT "${err}" MATCHES "compute for an image of fewer 64x64 llvmpipe tiles than its ${cpus} threads\\)")
    message(FATAL_ERROR "the switch to compute for a small image is not explained:\n${err}")
  endif()
endif()
expect("--backend;vulkan" 2 "--backend expects auto, fragment or compute, got 'vulkan'")
expect("--backend" 2 "--backend needs a value")
expect("--work-group;64x64" 2 "--work-group expects WxH")
message(STATUS "glint render --backend: fragment, compute, auto (timed, then cached) and bad values handled")

# A relative XDG_CACHE_HOME is ignored (the XDG Base Directory specification), by Glint and by the
# libraries it loads: the cache goes to $HOME/.cache, and nothing appears in the current folder.
file(MAKE_DIRECTORY "${OUT}/cwd" "${OUT}/home")
execute_process(COMMAND ${CMAKE_COMMAND} -E env XDG_CACHE_HOME=relative-cache HOME=${OUT}/home
                "${GLINT}" render "${PROJECT}" -o "${OUT}/out.png" --width 24 --spp 2
                WORKING_DIRECTORY "${OUT}/cwd" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR EXISTS "${OUT}/cwd/relative-cache" OR NOT EXISTS "${OUT}/home/.cache/glint/backend.json")
  file(GLOB_RECURSE made RELATIVE "${OUT}" "${OUT}/cwd/*" "${OUT}/home/*")
  message(FATAL_ERROR "a relative XDG_CACHE_HOME was not ignored (exit ${rc}; made: ${made})\n${err}")
endif()
