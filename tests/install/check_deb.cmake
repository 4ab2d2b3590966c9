# The .deb that CPack makes from the build BUILD (its CPackConfig.cmake, into OUT; the build is
# reused, only the install and the archive are made here): `dpkg-deb --info` names the package
# and declares its dependencies (the shared libraries glint links, from dpkg-shlibdeps, and the
# OpenGL drivers it loads), `dpkg-deb --contents` holds the installed files under /usr and no
# build files. OIDN (ON/OFF): the build bundles Open Image Denoise.
include(${CMAKE_CURRENT_LIST_DIR}/../expect_exit.cmake)
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
expect_exit(0 "" "${CPACK}" --config "${BUILD}/CPackConfig.cmake" -B "${OUT}")
file(GLOB debs "${OUT}/glint_*.deb")
list(LENGTH debs count)
if(NOT count EQUAL 1)
  message(FATAL_ERROR "cpack made ${count} .deb files in ${OUT}: ${debs}")
endif()

execute_process(COMMAND dpkg-deb --info ${debs} RESULT_VARIABLE rc OUTPUT_VARIABLE info ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "dpkg-deb --info ${debs}: exit ${rc}\n${err}")
endif()
foreach(field "Package: glint\n" "Version: ${VERSION}\n" "Section: graphics\n" "Maintainer: [^\n]+<[^\n]+@[^\n]+>\n"
        "Depends: [^\n]*libc6 \\(>= [^\n]*libepoxy0 \\(>= [^\n]*libstdc\\+\\+6 \\(>= "
        "Depends: [^\n]*libtinyexr[^\n]*libegl1, libgl1, libegl-mesa0 \\| libegl-vendor"
        "Depends: [^\n]*libglfw3 \\(>= " "Depends: [^\n]*libstb0 \\(>= " "Description: [^\n]+\n .*Open Image Denoise")
  if(NOT info MATCHES "${field}")
    message(FATAL_ERROR "dpkg-deb --info does not match '${field}':\n${info}")
  endif()
endforeach()

execute_process(COMMAND dpkg-deb --contents ${debs} RESULT_VARIABLE rc OUTPUT_VARIABLE contents ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "dpkg-deb --contents ${debs}: exit ${rc}\n${err}")
endif()
set(expected "-rwxr-xr-x [^\n]* ./usr/bin/glint\n" ./usr/share/glint/projects/cornell_box.glint
    ./usr/share/glint/projects/assets/checker.png ./usr/share/man/man1/glint.1.gz
    ./usr/share/applications/glint.desktop ./usr/share/icons/hicolor/scalable/apps/glint.svg
    ./usr/share/mime/packages/glint.xml ./usr/share/doc/glint/copyright ./usr/share/doc/glint/changelog.gz)
if(OIDN)
  list(APPEND expected "-rw-r--r-- [^\n]* ./usr/lib/glint/libOpenImageDenoise.so.2.5.1\n"
       ./usr/lib/glint/libOpenImageDenoise_device_cpu.so.2.5.1 ./usr/lib/glint/libtbb.so.12)
endif()
foreach(path IN LISTS expected)
  if(NOT contents MATCHES "${path}")
    message(FATAL_ERROR "dpkg-deb --contents lacks '${path}':\n${contents}")
  endif()
endforeach()
if(contents MATCHES "\\.(cpp|h|a|cmake)\n" OR contents MATCHES " \\./usr/(include|local)/")
  message(FATAL_ERROR "the package holds build files:\n${contents}")
endif()
