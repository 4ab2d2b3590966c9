# Intel Open Image Denoise 2.5.1, as Intel built it, from PyPI's pyoidn wheel: scripts/setup.sh
# downloads the wheel (pinned by hash, cmake/oidn-requirements.txt) into a cache outside the
# source tree; here its SHA-256 is checked again and the libraries glint loads at run time
# (renderer/denoiser.cpp, dlopen) are copied next to the executables with Intel's Apache-2.0
# notices. Nothing links against them: without the wheel (or off x86_64 Linux) glint builds the
# same and says that denoising is unavailable.
set(OIDN_VERSION 2.5.1)
set(OIDN_WHEEL_SHA256 32ad13368f8de1ef63001942ad05b02a00cd732d1206d97f352d3a3f606d823e)
if(DEFINED ENV{GLINT_DEPS_CACHE})
  set(_oidn_cache "$ENV{GLINT_DEPS_CACHE}")
elseif(DEFINED ENV{XDG_CACHE_HOME})
  set(_oidn_cache "$ENV{XDG_CACHE_HOME}/glint-deps")
else()
  set(_oidn_cache "$ENV{HOME}/.cache/glint-deps")
endif()
set(GLINT_OIDN_WHEEL "${_oidn_cache}/pyoidn-2.5.1.0-py3-none-manylinux2014_x86_64.whl"
    CACHE FILEPATH "The pyoidn 2.5.1.0 wheel that holds Open Image Denoise (scripts/setup.sh)")

set(GLINT_OIDN_AVAILABLE OFF)
if(NOT (CMAKE_SYSTEM_NAME STREQUAL "Linux" AND CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64"))
  message(STATUS "Open Image Denoise: x86_64 Linux only; denoising unavailable in this build")
  return()
endif()
if(NOT EXISTS "${GLINT_OIDN_WHEEL}")
  message(STATUS "Open Image Denoise: ${GLINT_OIDN_WHEEL} not found (scripts/setup.sh "
                 "downloads it); denoising unavailable in this build")
  return()
endif()

# The libraries glint loads (the CUDA plugin is loaded by OIDN itself when a CUDA driver is
# present; without one it is skipped).
set(_oidn_libs libOpenImageDenoise.so.${OIDN_VERSION} libOpenImageDenoise_core.so.${OIDN_VERSION}
    libOpenImageDenoise_device_cpu.so.${OIDN_VERSION} libOpenImageDenoise_device_cuda.so.${OIDN_VERSION}
    libtbb.so.12)
set(_oidn_dir "${CMAKE_BINARY_DIR}/_deps/oidn-${OIDN_VERSION}")
set(_oidn_stamp "${_oidn_dir}/wheel.sha256")
set(_have_sha "")
if(EXISTS "${_oidn_stamp}")
  file(READ "${_oidn_stamp}" _have_sha)
endif()
if(NOT _have_sha STREQUAL OIDN_WHEEL_SHA256)
  file(SHA256 "${GLINT_OIDN_WHEEL}" _sha)
  if(NOT _sha STREQUAL OIDN_WHEEL_SHA256)
    message(FATAL_ERROR "${GLINT_OIDN_WHEEL}: SHA-256 ${_sha} does not match the pinned ${OIDN_WHEEL_SHA256}")
  endif()
  file(REMOVE_RECURSE "${_oidn_dir}")
  set(_patterns pyoidn-2.5.1.0.dist-info/licenses/LICENSE pyoidn-2.5.1.0.dist-info/METADATA)
  foreach(lib IN LISTS _oidn_libs)
    list(APPEND _patterns pyoidn/oidn/lib/${lib})
  endforeach()
  message(STATUS "Open Image Denoise: extracting ${OIDN_VERSION} from ${GLINT_OIDN_WHEEL}")
  file(ARCHIVE_EXTRACT INPUT "${GLINT_OIDN_WHEEL}" DESTINATION "${_oidn_dir}" PATTERNS ${_patterns})
  file(WRITE "${_oidn_stamp}" "${OIDN_WHEEL_SHA256}")
endif()
foreach(lib IN LISTS _oidn_libs)
  if(NOT EXISTS "${_oidn_dir}/pyoidn/oidn/lib/${lib}")
    message(FATAL_ERROR "${GLINT_OIDN_WHEEL} lacks pyoidn/oidn/lib/${lib}")
  endif()
  file(COPY "${_oidn_dir}/pyoidn/oidn/lib/${lib}" DESTINATION "${CMAKE_BINARY_DIR}")
endforeach()
# The notices (cmake/OpenImageDenoise-NOTICE.txt says what each is): Intel's libraries are
# Apache-2.0; the wheel carries only its wrapper's MIT licence and its metadata.
set(_notices "${CMAKE_BINARY_DIR}/licenses/OpenImageDenoise")
file(MAKE_DIRECTORY "${_notices}/pyoidn")
file(COPY "${CMAKE_SOURCE_DIR}/cmake/OpenImageDenoise-NOTICE.txt" DESTINATION "${_notices}")
file(COPY_FILE /usr/share/common-licenses/Apache-2.0 "${_notices}/Apache-2.0.txt")
file(COPY "${_oidn_dir}/pyoidn-2.5.1.0.dist-info/licenses/LICENSE"
          "${_oidn_dir}/pyoidn-2.5.1.0.dist-info/METADATA" DESTINATION "${_notices}/pyoidn")
set(GLINT_OIDN_AVAILABLE ON)
message(STATUS "Open Image Denoise ${OIDN_VERSION}: libraries next to the executables in ${CMAKE_BINARY_DIR}")

set(GLINT_OIDN_LIBRARIES ${_oidn_libs})
# Installed (cmake/Packaging.cmake) in lib/glint/, where glint looks from its own folder, with the
# notices in the documentation's licenses/.
foreach(lib IN LISTS _oidn_libs)
  install(FILES "${CMAKE_BINARY_DIR}/${lib}" DESTINATION lib/glint)
endforeach()
install(DIRECTORY "${_notices}" DESTINATION share/doc/glint/licenses)
