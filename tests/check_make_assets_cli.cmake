# glint-make-assets' command line (GENERATOR), run in an empty folder OUT: --help prints the
# usage and exits 0, an unknown option exits 2 naming it, and neither creates a folder (the
# first argument was once taken as the output folder whatever it was: "--help" made one).
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")

include(${CMAKE_CURRENT_LIST_DIR}/expect_exit.cmake)
function(expect args rc_expected pattern)
  expect_exit("${rc_expected}" "${pattern}" ${CMAKE_COMMAND} -E chdir "${OUT}" "${GENERATOR}" ${args})
  file(GLOB made "${OUT}/*")
  if(made)
    message(FATAL_ERROR "glint-make-assets ${args} created ${made}")
  endif()
endfunction()

expect("--help" 0 "usage: glint-make-assets")
expect("-h" 0 "usage: glint-make-assets")
expect("--bogus;folder" 2 "unknown option --bogus")
expect("" 2 "expected OUTPUT_FOLDER")
expect("a;b;c" 2 "got 3 arguments")
message(STATUS "glint-make-assets: --help, unknown options and argument counts handled")
