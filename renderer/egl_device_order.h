// Which EGL device a render uses when a scheduler gave the process a GPU. Slurm (--gpus,
// --gpus-per-task) and other schedulers name the GPUs a job may use in CUDA_VISIBLE_DEVICES;
// CUDA renumbers devices by it but EGL's device list (EGL_EXT_device_enumeration) does not, so
// the GPU is found by the CUDA device number each NVIDIA EGL device reports
// (EGL_NV_device_cuda). Pure logic, so that the choice is testable without such a machine.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace glint {

struct EglDeviceOrder {
  std::vector<int> devices;  // indices into EGL's device list, in the order to try them
  std::string note;          // why, for the log ("" when CUDA_VISIBLE_DEVICES is not set)
};

// `cuda_visible`: CUDA_VISIBLE_DEVICES (nullopt when unset). `cuda_ids[i]`: the CUDA device
// number of EGL device i (nullopt for a device without EGL_NV_device_cuda: Mesa's, say).
// Unset: every device in EGL's order. Set: the device whose CUDA number is its first entry;
// if none matches (a scheduler that also hides the other GPUs, so the one left reports 0 or
// its own number), the first CUDA device; then the devices without CUDA (Mesa's software
// renderer), never another job's GPU. An empty value, or one CUDA rejects as well ("-1",
// "NoDevFiles"), leaves only the devices without CUDA.
EglDeviceOrder egl_device_order(const std::optional<std::string>& cuda_visible,
                                const std::vector<std::optional<int>>& cuda_ids);

}  // namespace glint
