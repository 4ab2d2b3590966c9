# glint_build_info: the version and the commit Glint was built from (renderer/build_info.h), for
# `glint --version` and the metadata of written images. The commit is read at configure time
# and again at every build (cmake/BuildInfoScript.cmake, git run with an argument vector); the
# generated source changes only when the commit does, so a new commit recompiles that one file
# and relinks (Ninja's restat on the byproduct), never a full rebuild.
find_package(Git QUIET)
set(_build_info "${CMAKE_BINARY_DIR}/generated/build_info.cpp")
set(_build_info_command ${CMAKE_COMMAND} "-DGIT=${GIT_EXECUTABLE}" "-DSOURCE_DIR=${CMAKE_SOURCE_DIR}"
    "-DVERSION=${PROJECT_VERSION}" "-DOUT=${_build_info}" -P "${CMAKE_SOURCE_DIR}/cmake/BuildInfoScript.cmake")
execute_process(COMMAND ${_build_info_command} COMMAND_ERROR_IS_FATAL ANY)
add_custom_target(glint_build_info_refresh COMMAND ${_build_info_command} BYPRODUCTS "${_build_info}" VERBATIM)
add_library(glint_build_info STATIC "${_build_info}")
add_dependencies(glint_build_info glint_build_info_refresh)
target_include_directories(glint_build_info PUBLIC "${CMAKE_SOURCE_DIR}")
