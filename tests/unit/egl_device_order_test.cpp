// The EGL device a render takes from CUDA_VISIBLE_DEVICES (renderer/egl_device_order.h).
#include <gtest/gtest.h>

#include "renderer/egl_device_order.h"

namespace glint {
namespace {

// EGL devices 0-2 are NVIDIA GPUs reporting CUDA numbers 0, 1, 2 in EGL's order; 3 is Mesa's.
const std::vector<std::optional<int>> kNodeDevices = {0, 1, 2, std::nullopt};

TEST(EglDeviceOrder, UnsetKeepsEglsOrder) {
  EXPECT_EQ(egl_device_order(std::nullopt, kNodeDevices).devices, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(egl_device_order(std::nullopt, kNodeDevices).note, "");
}

TEST(EglDeviceOrder, TakesTheGivenGpuThenSoftwareNeverAnotherGpu) {
  const EglDeviceOrder o = egl_device_order("2,0", kNodeDevices);
  EXPECT_EQ(o.devices, (std::vector<int>{2, 3}));
  EXPECT_NE(o.note.find("EGL device 2 is CUDA device 2"), std::string::npos) << o.note;
  // EGL's order need not be CUDA's.
  EXPECT_EQ(egl_device_order("1", {2, 1, 0}).devices, (std::vector<int>{1}));
}

TEST(EglDeviceOrder, AHiddenNumberingFallsBackToTheFirstCudaDevice) {
  // A scheduler that also hides the other GPUs (cgroups): one device left, numbered 0.
  EXPECT_EQ(egl_device_order("3", {0, std::nullopt}).devices, (std::vector<int>{0, 1}));
  EXPECT_EQ(egl_device_order("GPU-5c1e2b4f", {0, std::nullopt}).devices, (std::vector<int>{0, 1}));
}

TEST(EglDeviceOrder, NoGpuGivenLeavesSoftwareRendering) {
  for (const char* none : {"", "-1", "NoDevFiles"}) {
    const EglDeviceOrder o = egl_device_order(std::string(none), kNodeDevices);
    EXPECT_EQ(o.devices, (std::vector<int>{3})) << none;
    EXPECT_NE(o.note.find("software rendering"), std::string::npos) << o.note;
  }
  EXPECT_EQ(egl_device_order("0", {std::nullopt}).devices, (std::vector<int>{0}));  // a node without GPUs
}

}  // namespace
}  // namespace glint
