// Keeps the Vulkan loader from loading drivers that cannot find a device on this machine.
//
// The loader opens every driver its manifests name before it asks any of them for devices. Mesa's
// drivers for DRM hardware (anv and hasvk for Intel, radv for AMD, nvk for NVIDIA, venus for
// virtio-gpu) find their devices only among the render nodes /dev/dri/renderD*; on a machine with
// none (a CPU-only server, a container, CI) they find nothing, yet loading them delays every GPU
// command's start, ahead of the first pipeline (docs/performance.md, "The small-render floor").
// Where no render node exists and the user has not chosen drivers, vkray
// asks the loader to skip them (VK_LOADER_DRIVERS_DISABLE, Vulkan loader 1.3.234 and later; older
// loaders ignore it). The devices the loader lists are the same either way.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace vkray::gpu {

// Reads an environment variable: its value, or null where unset.
using EnvironmentLookup = std::function<const char*(const char*)>;

// The VK_LOADER_DRIVERS_DISABLE value that skips the DRM-only drivers, or nothing where they must
// stay: a render node exists, the user chose drivers (VK_ICD_FILENAMES, VK_DRIVER_FILES,
// VK_ADD_DRIVER_FILES, VK_LOADER_DRIVERS_SELECT or VK_LOADER_DRIVERS_DISABLE set, even empty), or
// radv is asked for its device without hardware (RADV_FORCE_FAMILY).
std::optional<std::string> driversWithoutDevices(const EnvironmentLookup& env, bool renderNodes);

// Whether `dri` holds a render node (renderD*).
bool hasRenderNode(const std::filesystem::path& dri = "/dev/dri");

// Applies driversWithoutDevices() to this process's environment. Call before any thread starts
// (it sets an environment variable) and before the first Vulkan instance.
void skipDriversWithoutDevices();

// What skipDriversWithoutDevices() told the loader to skip in this process, if anything (for
// `vkray devices`).
std::optional<std::string> skippedDrivers();

}  // namespace vkray::gpu
