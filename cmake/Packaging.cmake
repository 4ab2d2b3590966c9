# `cmake --install build --prefix P` and the .deb (`cmake --build build --target package`, CPack).
# The layout is relative, so that any prefix works and the installed tree can be moved:
#   P/bin/glint
#   P/lib/glint/          Open Image Denoise's libraries (renderer/denoiser.cpp: ../lib/glint
#                         from the executable's folder)
#   P/share/glint/projects/  the example projects and their assets (the editor finds them from
#                         the executable's folder: editor/editor_app.cpp)
#   P/share/applications, share/icons, share/mime/packages, share/man/man1: the desktop entry,
#                         the icon, the .glint file type and glint(1)
#   P/share/doc/glint/    copyright (Glint's and the bundled third parties' terms), licenses/
# Shaders are compiled into the executable (cmake/EmbedShaders.cmake): nothing to install.
set(GLINT_PACKAGE_MAINTAINER "Glint maintainers <maintainers@glint.invalid>"
    CACHE STRING "The .deb's Maintainer field and its changelog's signature")
install(TARGETS glint RUNTIME DESTINATION bin)
install(DIRECTORY "${CMAKE_SOURCE_DIR}/projects/" DESTINATION share/glint/projects
        FILES_MATCHING PATTERN "*.glint" PATTERN "assets/*.png" PATTERN "assets/*.hdr")
install(FILES "${CMAKE_SOURCE_DIR}/packaging/glint.desktop" DESTINATION share/applications)
install(FILES "${CMAKE_SOURCE_DIR}/packaging/glint.svg" DESTINATION share/icons/hicolor/scalable/apps)
install(FILES "${CMAKE_SOURCE_DIR}/packaging/glint-mime.xml" DESTINATION share/mime/packages RENAME glint.xml)

# glint(1), made from `glint --help` and its commands' --help at build time
# (cmake/ManPageScript.cmake), compressed without a timestamp as Debian wants it.
set(_man "${CMAKE_BINARY_DIR}/man/glint.1")
find_program(GZIP_EXECUTABLE gzip)
set(_man_commands COMMAND ${CMAKE_COMMAND} -DGLINT=$<TARGET_FILE:glint> -DVERSION=${PROJECT_VERSION}
                  -DOUT=${_man} -P "${CMAKE_SOURCE_DIR}/cmake/ManPageScript.cmake")
if(GZIP_EXECUTABLE)
  list(APPEND _man_commands COMMAND "${GZIP_EXECUTABLE}" -9nf "${_man}")
  set(_man "${_man}.gz")
endif()
add_custom_command(OUTPUT "${_man}" ${_man_commands}
                   DEPENDS glint "${CMAKE_SOURCE_DIR}/cmake/ManPageScript.cmake"
                   COMMENT "Writing glint(1) from glint --help" VERBATIM)
add_custom_target(glint_man_page ALL DEPENDS "${_man}")
install(FILES "${_man}" DESTINATION share/man/man1)

# Terms: Glint's and those of what is compiled in or shipped (packaging/copyright), with the
# third parties' own licence files.
install(FILES "${CMAKE_SOURCE_DIR}/packaging/copyright" DESTINATION share/doc/glint)
if(GLINT_BUILD_EDITOR)  # the folders where cmake/DearImGui.cmake and TinyFileDialogs.cmake fetch them
  install(FILES "${_imgui}/LICENSE.txt" DESTINATION share/doc/glint/licenses/DearImGui)
  install(FILES "${_implot}/LICENSE" DESTINATION share/doc/glint/licenses/ImPlot)
  # tinyfiledialogs states its copyright and zlib licence in its header's opening comment.
  file(READ "${_tfd_src}/libtinyfiledialogs/tinyfiledialogs.h" _tfd_header LIMIT 8192)
  if(NOT _tfd_header MATCHES "(Copyright \\(c\\) [^\n]+)\n.*- License -\n(.*)\n\\*/")
    message(FATAL_ERROR "tinyfiledialogs.h: no copyright line and licence found in its opening comment")
  endif()
  file(WRITE "${CMAKE_BINARY_DIR}/licenses/tinyfiledialogs/LICENSE" "${CMAKE_MATCH_1}\n\n${CMAKE_MATCH_2}\n")
  install(FILES "${CMAKE_BINARY_DIR}/licenses/tinyfiledialogs/LICENSE" DESTINATION share/doc/glint/licenses/tinyfiledialogs)
endif()
foreach(_dep nlohmann-json3-dev libglm-dev)
  if(EXISTS "/usr/share/doc/${_dep}/copyright")
    string(REGEX REPLACE "3?-dev$" "" _name "${_dep}")
    install(FILES "/usr/share/doc/${_dep}/copyright" DESTINATION share/doc/glint/licenses/${_name})
  endif()
endforeach()
# A native package's changelog, as Debian wants one: this version and the commit it was built
# from, rewritten when the commit changes.
if(GZIP_EXECUTABLE)
  set(_changelog "${CMAKE_BINARY_DIR}/packaging/changelog")
  add_custom_command(OUTPUT "${_changelog}.gz"
                     COMMAND ${CMAKE_COMMAND} -DBUILD_INFO=${_build_info} -DVERSION=${PROJECT_VERSION}
                             "-DMAINTAINER=${GLINT_PACKAGE_MAINTAINER}" -DOUT=${_changelog}
                             -P "${CMAKE_SOURCE_DIR}/cmake/ChangelogScript.cmake"
                     COMMAND "${GZIP_EXECUTABLE}" -9nf "${_changelog}"
                     DEPENDS "${_build_info}" "${CMAKE_SOURCE_DIR}/cmake/ChangelogScript.cmake" VERBATIM)
  add_custom_target(glint_changelog ALL DEPENDS "${_changelog}.gz")
  install(FILES "${_changelog}.gz" DESTINATION share/doc/glint RENAME changelog.gz)
endif()

# The Debian package: the files above under /usr, with lintian's overrides (each says why).
install(FILES "${CMAKE_SOURCE_DIR}/packaging/lintian-overrides" DESTINATION share/lintian/overrides RENAME glint)
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME glint)
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "scene editor with a progressive GPU path tracer")
set(CPACK_PACKAGE_DESCRIPTION "Glint edits scenes of spheres and quads with matte, glossy, mirror,
glass and emissive materials, textures and an HDR environment, around a live
path-traced viewport (GLFW and Dear ImGui). glint render renders a project
headlessly through EGL to PNG, HDR or EXR; glint merge and glint farm split a
render over a Slurm cluster. Denoising uses Intel Open Image Denoise, shipped
with the package.")
set(CPACK_PACKAGE_CONTACT "${GLINT_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${GLINT_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
# The shared-library dependencies: dpkg-shlibdeps at packaging time (cmake/DebianDepends.cmake.in).
find_program(DPKG_SHLIBDEPS dpkg-shlibdeps)
if(DPKG_SHLIBDEPS)
  set(GLINT_EXECUTABLE_PATH "${CMAKE_BINARY_DIR}/glint")
  set(GLINT_SHLIBDEPS_LIBRARIES "")
  foreach(_lib IN LISTS GLINT_OIDN_LIBRARIES)
    if(NOT _lib MATCHES "_device_cuda")
      string(APPEND GLINT_SHLIBDEPS_LIBRARIES " \"${CMAKE_BINARY_DIR}/${_lib}\"")
    endif()
  endforeach()
  configure_file("${CMAKE_SOURCE_DIR}/cmake/DebianDepends.cmake.in" "${CMAKE_BINARY_DIR}/DebianDepends.cmake" @ONLY)
  set(CPACK_PROJECT_CONFIG_FILE "${CMAKE_BINARY_DIR}/DebianDepends.cmake")
endif()
# Mesa's drivers: glint loads OpenGL through libepoxy and EGL at run time, which dpkg-shlibdeps
# cannot see.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl1, libgl1, libegl-mesa0 | libegl-vendor, libgl1-mesa-dri")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "xvfb")
set(CPACK_STRIP_FILES ON)
set(CPACK_PACKAGE_DIRECTORY "${CMAKE_BINARY_DIR}/package")
include(CPack)
