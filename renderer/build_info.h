// What this build of Glint is: its version and the commit it was built from. Defined in a source
// generated at build time (cmake/BuildInfo.cmake).
#pragma once

#include <string>

namespace glint {

// The project's version, e.g. "0.1".
const char* glint_version();
// `git describe --always --dirty --abbrev=12` of the source it was built from (e.g.
// "42cfb04d0e1a-dirty"), or "unknown" when built outside a git work tree.
const char* glint_commit();
// "Glint 0.1 (42cfb04d0e1a)": what `glint --version` prints first and the "Software" of the
// images Glint writes.
std::string glint_software();

}  // namespace glint
