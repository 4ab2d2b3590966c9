#include "renderer/build_info.h"

namespace glint {

std::string glint_software() {
  return std::string("Glint ") + glint_version() + " (" + glint_commit() + ")";
}

}  // namespace glint
