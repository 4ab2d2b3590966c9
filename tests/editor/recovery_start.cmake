# editor.recovery_start: the real editor starts while recoveries exist (in a state folder of its
# own): one left by a crashed session (recovery-ID.glint, its lock file gone), one of an older
# editor (the fixed name recovery.glint), and one of a session still running (its lock held by
# flock(1) around the editor). It must not abort, must offer the first two and not the running
# one and, closed by --frames with the offers unanswered, exit 0 and keep them all.
# Arguments: GLINT, PROJECT, DIR (a scratch folder).
file(REMOVE_RECURSE "${DIR}")
set(state "${DIR}/state/glint")
file(MAKE_DIRECTORY "${DIR}/home" "${state}")
get_filename_component(projects "${PROJECT}" DIRECTORY)
set(sidecar "{\"original\": \"${PROJECT}\", \"base_dir\": \"${projects}\"}\n")
foreach(stem recovery recovery-00000000000000a1 recovery-00000000000000b2)
  configure_file("${PROJECT}" "${state}/${stem}.glint" COPYONLY)
  file(WRITE "${state}/${stem}.json" "${sidecar}")
endforeach()
set(ENV{HOME} "${DIR}/home")
set(ENV{XDG_STATE_HOME} "${DIR}/state")
set(ENV{XDG_CONFIG_HOME} "${DIR}/config")
set(ENV{GLINT_NO_NATIVE_DIALOGS} 1)
execute_process(COMMAND flock --nonblock "${state}/recovery-00000000000000b2.lock"
                        xvfb-run -a -s "-screen 0 1280x800x24" "${GLINT}" "${PROJECT}" --size 800x500 --frames 20
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out TIMEOUT 240)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "glint with recoveries on offer failed (exit ${rc})")
endif()
string(REGEX MATCHALL "offering the unsaved work[^\n]*" offers "${out}")
list(LENGTH offers count)
if(NOT count EQUAL 2 OR NOT out MATCHES "recovery-00000000000000a1.glint" OR NOT out MATCHES "recovery.glint")
  message(FATAL_ERROR "glint did not offer the crashed session's and the older editor's recoveries: ${offers}")
endif()
if(out MATCHES "recovery-00000000000000b2")
  message(FATAL_ERROR "glint offered the recovery of a session that is still running")
endif()
foreach(stem recovery recovery-00000000000000a1 recovery-00000000000000b2)
  if(NOT EXISTS "${state}/${stem}.glint" OR NOT EXISTS "${state}/${stem}.json")
    message(FATAL_ERROR "the recovery ${stem} was deleted")
  endif()
endforeach()
