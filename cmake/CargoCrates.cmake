# Pinned crates from crates.io, fetched by cargo (sparse index) at configure time and unpacked
# once their SHA-256 matches: how Dear ImGui (DearImGui.cmake) and tinyfiledialogs
# (TinyFileDialogs.cmake) get their C and C++ sources. Nothing of them is copied into the
# repository.
include_guard(GLOBAL)

find_program(CARGO_EXECUTABLE cargo HINTS "$ENV{HOME}/.cargo/bin" REQUIRED)

# Runs `cargo fetch` for the manifest in MANIFEST_DIR (Cargo.toml, src/lib.rs and, when there,
# Cargo.lock, which then pins every crate: --locked), copied into WORK_DIR first. WHAT names the
# crates in the messages.
function(glint_cargo_fetch WHAT MANIFEST_DIR WORK_DIR)
  file(MAKE_DIRECTORY "${WORK_DIR}/src")
  set(_args fetch)
  foreach(_f Cargo.toml Cargo.lock src/lib.rs)
    if(EXISTS "${MANIFEST_DIR}/${_f}")
      configure_file("${MANIFEST_DIR}/${_f}" "${WORK_DIR}/${_f}" COPYONLY)
    endif()
  endforeach()
  if(EXISTS "${MANIFEST_DIR}/Cargo.lock")
    list(APPEND _args --locked)
  endif()
  message(STATUS "Fetching ${WHAT} with cargo")
  execute_process(COMMAND "${CARGO_EXECUTABLE}" ${_args} --manifest-path "${WORK_DIR}/Cargo.toml"
                  RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "cargo fetch of ${WHAT} failed:\n${_out}")
  endif()
endfunction()

# Unpacks NAME-VERSION.crate from cargo's download cache ($CARGO_HOME, else ~/.cargo) into
# DESTINATION (as DESTINATION/NAME-VERSION/) once its SHA-256 is SHA256; a fatal error otherwise.
function(glint_extract_crate NAME VERSION SHA256 DESTINATION)
  if(DEFINED ENV{CARGO_HOME})
    set(_cargo_home "$ENV{CARGO_HOME}")
  else()
    set(_cargo_home "$ENV{HOME}/.cargo")
  endif()
  file(GLOB _crates "${_cargo_home}/registry/cache/*/${NAME}-${VERSION}.crate")
  list(LENGTH _crates _n)
  if(_n EQUAL 0)
    message(FATAL_ERROR "${NAME}-${VERSION}.crate not found under ${_cargo_home}/registry/cache")
  endif()
  list(GET _crates 0 _crate)
  file(SHA256 "${_crate}" _sha)
  if(NOT "${_sha}" STREQUAL "${SHA256}")
    message(FATAL_ERROR "${_crate}: SHA-256 ${_sha} does not match the pinned ${SHA256}")
  endif()
  file(ARCHIVE_EXTRACT INPUT "${_crate}" DESTINATION "${DESTINATION}")
endfunction()
