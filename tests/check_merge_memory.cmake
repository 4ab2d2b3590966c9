# `glint merge` (GLINT) of 32 parts of 960x540 that MAKE_PARTS writes into OUT, under an
# address-space cap of 160 MiB (prlimit --as). The parts take 8.3 MB each decoded, 265 MB
# together, so a merge that holds them all fails (the merge that did needed between 192 and 320
# MiB); one that reads them one at a time holds the film's sums (16.6 MB) and one part, and
# merged them under a 56 MiB cap here: the cap leaves it about three times that.
include(${CMAKE_CURRENT_LIST_DIR}/expect_exit.cmake)
file(REMOVE_RECURSE "${OUT}")
expect_exit(0 "wrote 32 parts of 960x540" "${MAKE_PARTS}" "${OUT}/parts" 32 960 540)
file(GLOB parts "${OUT}/parts/part-*.exr")
list(SORT parts)
find_program(PRLIMIT prlimit REQUIRED)
math(EXPR cap "160 * 1024 * 1024")
expect_exit(0 "wrote .*merged.exr \\(960x540, 32 parts, samples 0:32\\)"
            "${PRLIMIT}" --as=${cap} "${GLINT}" merge --spp 32 ${parts} -o "${OUT}/merged.exr")
file(REMOVE_RECURSE "${OUT}")
