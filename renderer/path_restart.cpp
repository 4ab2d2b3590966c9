#include "renderer/path_restart.h"

namespace glint {

bool environment_emits(const Environment& env) {
  if (!(env.intensity > 0)) return false;
  if (!env.texture.empty()) return true;
  return env.color.r > 0 || env.color.g > 0 || env.color.b > 0;
}

bool restart_paths_together(PathRestart restart, const Environment& env) {
  switch (restart) {
    case PathRestart::at_once: return false;
    case PathRestart::together: return true;
    case PathRestart::automatic: break;
  }
  return environment_emits(env);
}

}  // namespace glint
