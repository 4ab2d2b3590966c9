# cmake/BuildInfoScript.cmake against a git repository of the test's own in OUT: the commit is
# that of HEAD, "-dirty" with a changed tracked file, refreshed by a new commit and left alone
# (not rewritten) at the same commit; "unknown" without git, in a folder that is not the top of
# a work tree (one inside a repository) and in a folder under no repository.
# GIT: the git program. SCRIPT: BuildInfoScript.cmake. OUT: a scratch folder.
file(REMOVE_RECURSE "${OUT}")
set(repo "${OUT}/repo")
file(MAKE_DIRECTORY "${repo}")
set(generated "${OUT}/build_info.cpp")
# The repository's parent bounds git's search: nothing above OUT is asked.
set(ENV{GIT_CEILING_DIRECTORIES} "${OUT}")

function(run_git)
  execute_process(COMMAND "${GIT}" -C "${repo}" -c user.name=glint-test -c user.email=test@glint.invalid
                          -c commit.gpgsign=false ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "git ${ARGN}: exit ${rc}\n${out}${err}")
  endif()
  set(git_out "${out}" PARENT_SCOPE)
endfunction()

function(generate source_dir git)
  execute_process(COMMAND "${CMAKE_COMMAND}" "-DGIT=${git}" "-DSOURCE_DIR=${source_dir}" -DVERSION=9.8
                          "-DOUT=${generated}" -P "${SCRIPT}" RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "BuildInfoScript.cmake failed: ${err}")
  endif()
endfunction()

function(expect_commit expected why)
  file(READ "${generated}" text)
  string(FIND "${text}" "glint_commit() { return \"${expected}\"; }" at)
  string(FIND "${text}" "glint_version() { return \"9.8\"; }" version_at)
  if(at LESS 0 OR version_at LESS 0)
    message(FATAL_ERROR "${why}: expected version 9.8 and commit ${expected}, the generated source is:\n${text}")
  endif()
endfunction()

run_git(init -q)
file(WRITE "${repo}/a.txt" "one\n")
run_git(add a.txt)
run_git(commit -q -m one)
run_git(rev-parse --short=12 HEAD)
set(first "${git_out}")
generate("${repo}" "${GIT}")
expect_commit("${first}" "a first commit")

# The same commit again: the file is not rewritten (nothing that includes it recompiles).
file(TIMESTAMP "${generated}" before "%s")
execute_process(COMMAND "${CMAKE_COMMAND}" -E sleep 1.1)
generate("${repo}" "${GIT}")
file(TIMESTAMP "${generated}" after "%s")
if(NOT before STREQUAL after)
  message(FATAL_ERROR "the generated source was rewritten at the same commit (${before} -> ${after})")
endif()

file(WRITE "${repo}/a.txt" "changed\n")
generate("${repo}" "${GIT}")
expect_commit("${first}-dirty" "a changed tracked file")

run_git(commit -q -a -m two)
run_git(rev-parse --short=12 HEAD)
set(second "${git_out}")
if(second STREQUAL first)
  message(FATAL_ERROR "the second commit has the first one's hash")
endif()
generate("${repo}" "${GIT}")
expect_commit("${second}" "a new commit")

generate("${repo}" "")
expect_commit("unknown" "no git program")
file(MAKE_DIRECTORY "${repo}/inner")
generate("${repo}/inner" "${GIT}")
expect_commit("unknown" "a folder inside a repository, not its top")
file(MAKE_DIRECTORY "${OUT}/plain")
generate("${OUT}/plain" "${GIT}")
expect_commit("unknown" "a folder under no repository")
