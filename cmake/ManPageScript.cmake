# Writes OUT, glint(1) in troff, from what GLINT prints for `--help` and for the `--help` of
# render, merge, farm and convert: the manual page is that text, so the two cannot drift. The
# first line of `glint --help` ("glint: WHAT") is the page's NAME. VERSION is the footer.
# The text is set verbatim (.nf) with troff's special characters escaped.
function(run_help out_var)
  execute_process(COMMAND "${GLINT}" ${ARGN} --help RESULT_VARIABLE rc OUTPUT_VARIABLE text ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR text STREQUAL "")
    string(REPLACE ";" " " shown "${ARGN}")
    message(FATAL_ERROR "glint ${shown} --help: exit ${rc}, no manual page made\n${err}")
  endif()
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()

# Verbatim text as troff: backslashes as \e, minus signs as \- (options stay searchable and
# copyable), and a line that starts with a control character (. or ') guarded by \&.
function(troff_verbatim out_var text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REPLACE "-" "\\-" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  string(REGEX REPLACE "\n+$" "" text "${text}")
  set(${out_var} ".nf\n${text}\n.fi\n" PARENT_SCOPE)
endfunction()

run_help(main)
if(NOT main MATCHES "^glint: ([^\n]+)\n\n?(.*)$")
  message(FATAL_ERROR "glint --help does not start with 'glint: WHAT', no manual page made")
endif()
set(what "${CMAKE_MATCH_1}")
set(rest "${CMAKE_MATCH_2}")
string(REPLACE "\\" "\\e" what "${what}")
string(REPLACE "-" "\\-" what "${what}")
troff_verbatim(page_main "${rest}")
set(page ".\\\" Generated from `glint --help` and its commands' --help by cmake/ManPageScript.cmake.
.TH GLINT 1 \"\" \"Glint ${VERSION}\" \"User Commands\"
.SH NAME
glint \\- ${what}
.SH SYNOPSIS
${page_main}")
foreach(command render merge farm convert)
  run_help(text ${command})
  troff_verbatim(body "${text}")
  string(TOUPPER "${command}" title)
  string(APPEND page ".SH \"GLINT ${title}\"\n${body}")
endforeach()
string(APPEND page ".SH FILES
.TP
.I PREFIX/share/glint/projects/
the example projects (the editor's File > Examples opens them as untitled copies)
.TP
.I PREFIX/lib/glint/
Intel Open Image Denoise, which \\-\\-denoise loads
")
file(WRITE "${OUT}" "${page}")
