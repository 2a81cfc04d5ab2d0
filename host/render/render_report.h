// What one scene of a render session did: filled as the render goes; the CLI prints it for people
// or as JSON for scripts (cli/report_printing.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "frame/render_options.h"
#include "gpu/gpu_render_report.h"
#include "render/memory_budget.h"

namespace vkray::render {

// A structure file the render read (--load-accel) or wrote (--save-accel), and how long that took.
struct AccelFileReport {
    std::string path;
    bool loaded = false;  // else saved
    double ms = 0.0;
};

struct RenderReport {
    std::string scene;   // the scene file as given
    std::string device;  // "llvmpipe (...) (Mesa ...)" or the CPU reference
    std::string output;  // the colour image written
    std::map<std::string, std::string> aovs;  // AOV name -> file written
    RenderOptions options;
    std::string accel;   // the accelerator's name
    double buildMs = 0.0;  // none when the structure was loaded from a file
    // Of buildMs, the structure's arrays in the kernel's layout (GPU renders and --save-accel).
    std::optional<double> gpuDataMs;
    std::optional<AccelFileReport> accelFile;
    std::vector<accel::AccelStat> accelStats;
    size_t triangles = 0, materials = 0, lights = 0;
    std::array<double, 3> origin{};  // Scene::origin: where the scene's local floats are measured from
    double loadMs = 0.0, renderMs = 0.0;
    // GPU renders: how long the scene waited for the Vulkan device, opened on a thread while it
    // loaded (the loader, the driver and its compiler start; 0 once an earlier scene opened it).
    std::optional<double> deviceMs;
    double writeMs = 0.0;  // the image and AOV files
    double totalMs = 0.0;  // the whole scene until the images are written: load, build, render, output
    std::optional<gpu::GpuRenderReport> gpu;  // GPU renders only
    bool buildOnly = false;  // the structure built and saved, nothing rendered
    MemoryReport memory;
};

}  // namespace vkray::render
