# Writes OUT, the changelog a native Debian package carries: this VERSION and the commit it was
# built from (read from BUILD_INFO, the generated source of renderer/build_info.h), signed by
# MAINTAINER, dated now (or $SOURCE_DATE_EPOCH, for a reproducible package).
file(READ "${BUILD_INFO}" info)
set(commit unknown)
if(info MATCHES "glint_commit\\(\\) { return \"([^\"]*)\"")
  set(commit "${CMAKE_MATCH_1}")
endif()
string(TIMESTAMP date "%a, %d %b %Y %H:%M:%S +0000" UTC)
file(WRITE "${OUT}" "glint (${VERSION}) unstable; urgency=medium

  * Glint ${VERSION}, built from commit ${commit}.

 -- ${MAINTAINER}  ${date}
")
