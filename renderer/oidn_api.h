// The few functions and constants of Intel Open Image Denoise's C API (2.x) that
// renderer/denoiser.cpp uses, declared from its public API documentation
// (https://github.com/RenderKit/oidn, doc/api.md) as function-pointer types: glint does not
// link the library but loads it at run time (dlopen), so that it builds and runs without it.
#pragma once

#include <cstddef>

namespace glint::oidn {

// Opaque handles.
using Device = struct OIDNDeviceImpl*;
using Buffer = struct OIDNBufferImpl*;
using Filter = struct OIDNFilterImpl*;

// OIDNDeviceType: DEFAULT picks the fastest device present (a CUDA GPU over the CPU).
enum DeviceType : int { kDeviceDefault = 0, kDeviceCpu = 1, kDeviceSycl = 2, kDeviceCuda = 3,
                        kDeviceHip = 4, kDeviceMetal = 5 };
// OIDNError
enum Error : int { kErrorNone = 0 };
// OIDNFormat: three float32 channels per pixel.
enum Format : int { kFormatFloat3 = 3 };
// OIDNQuality, the RT filter's "quality" parameter.
enum Quality : int { kQualityFast = 4, kQualityBalanced = 5, kQualityHigh = 6 };

extern "C" {
using NewDeviceFn = Device (*)(int type);
using CommitDeviceFn = void (*)(Device);
using GetDeviceIntFn = int (*)(Device, const char* name);
using GetDeviceErrorFn = int (*)(Device, const char** message);
using ReleaseDeviceFn = void (*)(Device);
using NewBufferFn = Buffer (*)(Device, size_t byte_size);
using WriteBufferFn = void (*)(Buffer, size_t byte_offset, size_t byte_size, const void* source);
using ReadBufferFn = void (*)(Buffer, size_t byte_offset, size_t byte_size, void* destination);
using ReleaseBufferFn = void (*)(Buffer);
using NewFilterFn = Filter (*)(Device, const char* type);
using SetFilterImageFn = void (*)(Filter, const char* name, Buffer, int format, size_t width,
                                  size_t height, size_t byte_offset, size_t pixel_byte_stride,
                                  size_t row_byte_stride);
using UnsetFilterImageFn = void (*)(Filter, const char* name);
using SetFilterBoolFn = void (*)(Filter, const char* name, bool value);
using SetFilterIntFn = void (*)(Filter, const char* name, int value);
using CommitFilterFn = void (*)(Filter);
using ExecuteFilterFn = void (*)(Filter);
using ReleaseFilterFn = void (*)(Filter);
}

}  // namespace glint::oidn
