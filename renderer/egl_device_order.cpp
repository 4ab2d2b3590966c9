#include "renderer/egl_device_order.h"

#include <cstdlib>

namespace glint {

EglDeviceOrder egl_device_order(const std::optional<std::string>& cuda_visible,
                                const std::vector<std::optional<int>>& cuda_ids) {
  EglDeviceOrder order;
  const int n = static_cast<int>(cuda_ids.size());
  if (!cuda_visible) {
    for (int i = 0; i < n; ++i) order.devices.push_back(i);
    return order;
  }
  // The first entry, if it is a device number (UUIDs and MIG names are not matched by number).
  const std::string first = cuda_visible->substr(0, cuda_visible->find(','));
  std::optional<int> wanted;
  if (!first.empty() && first.find_first_not_of("0123456789") == std::string::npos && first.size() < 6)
    wanted = std::atoi(first.c_str());
  std::optional<int> gpu;
  for (int i = 0; i < n && wanted; ++i)
    if (cuda_ids[i] == wanted) {
      gpu = i;
      order.note = "CUDA_VISIBLE_DEVICES=" + *cuda_visible + ": EGL device " + std::to_string(i) +
                   " is CUDA device " + std::to_string(*wanted);
    }
  if (!gpu && !first.empty() && first != "-1" && first != "NoDevFiles")
    for (int i = 0; i < n && !gpu; ++i)
      if (cuda_ids[i]) {
        gpu = i;
        order.note = "CUDA_VISIBLE_DEVICES=" + *cuda_visible + ": no EGL device reports CUDA device " + first +
                     "; the first CUDA device, EGL device " + std::to_string(i);
      }
  if (gpu) order.devices.push_back(*gpu);
  else order.note = "CUDA_VISIBLE_DEVICES=" + *cuda_visible + ": no GPU given; software rendering";
  for (int i = 0; i < n; ++i)
    if (!cuda_ids[i]) order.devices.push_back(i);
  return order;
}

}  // namespace glint
