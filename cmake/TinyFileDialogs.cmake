# tinyfiledialogs from its published crate on crates.io, fetched by cargo, pinned to one version
# and checked against a SHA-256 here (CargoCrates.cmake); its C files are compiled as a static
# library.
set(TFD_VERSION 3.9.1)
set(TFD_SHA256 e25fa0bc43a6566e2cc6d7ac96df3fa5a57beba34445bead1b368ba8fe9ca568)

include(${CMAKE_CURRENT_LIST_DIR}/CargoCrates.cmake)
set(_tfd_src "${CMAKE_BINARY_DIR}/_deps/tinyfiledialogs-${TFD_VERSION}")

if(NOT EXISTS "${_tfd_src}/libtinyfiledialogs/tinyfiledialogs.c")
  glint_cargo_fetch("tinyfiledialogs ${TFD_VERSION}" "${CMAKE_SOURCE_DIR}/cmake/tinyfiledialogs-crate"
                    "${CMAKE_BINARY_DIR}/_deps/tinyfiledialogs-fetch")
  glint_extract_crate(tinyfiledialogs ${TFD_VERSION} ${TFD_SHA256} "${CMAKE_BINARY_DIR}/_deps")
endif()

add_library(tinyfiledialogs STATIC "${_tfd_src}/libtinyfiledialogs/tinyfiledialogs.c")
target_include_directories(tinyfiledialogs SYSTEM PUBLIC "${_tfd_src}/libtinyfiledialogs")
set_target_properties(tinyfiledialogs PROPERTIES C_STANDARD 99 POSITION_INDEPENDENT_CODE ON)
target_compile_options(tinyfiledialogs PRIVATE -w)
