# editor.recovery_start: the real editor starts while a crashed run's recovery file exists (in a
# state folder of its own): it must not abort, must offer the recovery and, closed by --frames
# with the offer unanswered, exit 0 and keep the recovery for the next start.
# Arguments: GLINT, PROJECT, DIR (a scratch folder).
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}/home" "${DIR}/state/glint")
get_filename_component(projects "${PROJECT}" DIRECTORY)
configure_file("${PROJECT}" "${DIR}/state/glint/recovery.glint" COPYONLY)
file(WRITE "${DIR}/state/glint/recovery.json"
     "{\"original\": \"${PROJECT}\", \"base_dir\": \"${projects}\"}\n")
set(ENV{HOME} "${DIR}/home")
set(ENV{XDG_STATE_HOME} "${DIR}/state")
set(ENV{XDG_CONFIG_HOME} "${DIR}/config")
set(ENV{GLINT_NO_NATIVE_DIALOGS} 1)
execute_process(COMMAND xvfb-run -a -s "-screen 0 1280x800x24" "${GLINT}" "${PROJECT}" --size 800x500 --frames 20
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "glint with a recovery on offer failed (exit ${rc})")
endif()
if(NOT out MATCHES "offering the unsaved work")
  message(FATAL_ERROR "glint did not offer the recovery")
endif()
if(NOT EXISTS "${DIR}/state/glint/recovery.glint")
  message(FATAL_ERROR "the unanswered recovery was deleted")
endif()
