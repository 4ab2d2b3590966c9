# `cmake --install` of the build BUILD into a prefix under OUT, then the prefix moved elsewhere
# (the layout is relative, so any prefix works) and glint run from a third folder: --version,
# and `glint render` of an example project with textures, with --denoise when the build bundles
# Open Image Denoise (OIDN: ON/OFF; then it must be found in the prefix's lib/glint). Checks
# the files a user gets: the manual page (rendered by man without warnings where man is
# installed), the desktop entry, the icon, the file type, the terms.
include(${CMAKE_CURRENT_LIST_DIR}/../expect_exit.cmake)
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}/elsewhere")
expect_exit(0 "" "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${OUT}/installed")
file(RENAME "${OUT}/installed" "${OUT}/moved")
set(prefix "${OUT}/moved")

set(expected bin/glint share/glint/projects/default.glint share/glint/projects/textured_spheres.glint
    share/glint/projects/assets/sky.hdr share/glint/projects/assets/wood_color.png
    share/man/man1/glint.1.gz share/applications/glint.desktop share/icons/hicolor/scalable/apps/glint.svg
    share/mime/packages/glint.xml share/doc/glint/copyright share/doc/glint/changelog.gz)
if(OIDN)
  list(APPEND expected lib/glint/libOpenImageDenoise.so.2.5.1 lib/glint/libOpenImageDenoise_core.so.2.5.1
       lib/glint/libOpenImageDenoise_device_cpu.so.2.5.1 lib/glint/libtbb.so.12
       share/doc/glint/licenses/OpenImageDenoise/Apache-2.0.txt)
endif()
foreach(f IN LISTS expected)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "the installed tree lacks ${f}")
  endif()
endforeach()
file(GLOB_RECURSE stray RELATIVE "${prefix}" "${prefix}/*.cpp" "${prefix}/*.a" "${prefix}/*.h")
if(stray)
  message(FATAL_ERROR "the installed tree holds build files: ${stray}")
endif()

# Run as a user would: from another folder, with nothing pointing at the build.
unset(ENV{GLINT_OIDN_DIR})
set(glint "${prefix}/bin/glint")
execute_process(COMMAND "${glint}" --version WORKING_DIRECTORY "${OUT}/elsewhere"
                RESULT_VARIABLE rc OUTPUT_VARIABLE version)
if(NOT rc EQUAL 0 OR NOT version MATCHES "^glint [0-9.]+ \\(commit [^)]+\\)")
  message(FATAL_ERROR "installed glint --version: exit ${rc}, '${version}'")
endif()
set(render render "${prefix}/share/glint/projects/textured_spheres.glint" -o picture.png --width 32 --spp 2)
set(pattern "wrote picture.png \\(32x")
if(OIDN)
  list(APPEND render --denoise)
  set(pattern "denoised \\(biased\\) with Open Image Denoise.*${pattern}")
endif()
execute_process(COMMAND "${glint}" ${render} WORKING_DIRECTORY "${OUT}/elsewhere"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT "${out}${err}" MATCHES "${pattern}" OR NOT EXISTS "${OUT}/elsewhere/picture.png")
  message(FATAL_ERROR "installed glint ${render}: exit ${rc}, output does not match '${pattern}':\n${out}${err}")
endif()

# The manual page as man shows it: troff without a warning, the options of every command.
find_program(MAN man)
if(MAN)
  execute_process(COMMAND "${MAN}" --warnings -E UTF-8 -l -Tutf8 -Z "${prefix}/share/man/man1/glint.1.gz"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE page ERROR_VARIABLE warnings)
  if(NOT rc EQUAL 0 OR NOT warnings STREQUAL "")
    message(FATAL_ERROR "man glint.1.gz: exit ${rc}:\n${warnings}")
  endif()
  execute_process(COMMAND "${MAN}" -l -P cat "${prefix}/share/man/man1/glint.1.gz" OUTPUT_VARIABLE page)
  foreach(text "--screenshot FILE" "--denoise-quality" "glint merge PART.exr" "--gpus-per-task")
    string(FIND "${page}" "${text}" at)
    if(at LESS 0)
      message(FATAL_ERROR "man glint does not show '${text}':\n${page}")
    endif()
  endforeach()
endif()

# The file type as shared-mime-info compiles it (where it is installed): *.glint is
# application/x-glint-project.
find_program(UPDATE_MIME_DATABASE update-mime-database)
if(UPDATE_MIME_DATABASE)
  file(COPY "${prefix}/share/mime" DESTINATION "${OUT}/mime-check")
  expect_exit(0 "" "${UPDATE_MIME_DATABASE}" "${OUT}/mime-check/mime")
  file(READ "${OUT}/mime-check/mime/globs2" globs)
  if(NOT globs MATCHES "application/x-glint-project:\\*\\.glint")
    message(FATAL_ERROR "update-mime-database did not register *.glint:\n${globs}")
  endif()
endif()
