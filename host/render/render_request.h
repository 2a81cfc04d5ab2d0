// What a render session is asked: how every scene of a call is rendered and written, with no
// command-line types (the CLI fills it from its flags; tests fill it directly).
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "accel/accel_spec.h"
#include "core/phase_log.h"
#include "cpu/reference_renderer.h"
#include "frame/render_options.h"
#include "gpu/gpu_render_report.h"
#include "image/image_meta.h"
#include "scene/scene.h"
#include "scene/text_input.h"

namespace vkray::render {

// What one scene is rendered with, known once it is loaded (its size, depth and samples are the
// defaults that a request overrides).
struct SceneSettings {
    RenderOptions options;
    std::optional<glm::vec3> background;  // overrides the scene's
    Encoding encoding;                    // of 8-bit outputs
    std::filesystem::path output;         // the colour image; empty: none
};

// Progress of the long steps, for a progress line; each may be empty.
struct Progress {
    std::function<void(const std::string& step)> load;  // a step of a scene's load that may take seconds
    BuildProgress build;                                 // the structure's build phases
    gpu::TileProgress tiles;                             // GPU renders
    RenderProgress rows;                                 // CPU renders
    std::function<void()> lineDone;                      // after a load, and after a build with phases
};

struct RenderRequest {
    accel::AccelSpec accel;    // resolved and validated (accel::resolveAccel)
    std::string view = "scene";  // the camera (scene/camera.h, viewCamera)
    bool cpu = false;          // the CPU reference (double precision) instead of the GPU
    std::string device;        // the Vulkan device: index or name substring; empty: vkray's choice
    bool buildOnly = false;    // build the structure and save it, render nothing
    std::filesystem::path saveAccel, loadAccel;   // structure files (accel/accel_file.h); empty: none
    std::map<std::string, std::string> aovs;      // AOV name -> file, every scene's
    std::optional<IndexOfCount> tile;             // a band of a tiled render: recorded in EXR outputs
    bool tracePixel = false;   // trace the window's first pixel's centre ray on the CPU too
    // The settings of each scene once it is loaded, its camera set (file: as given). May throw.
    std::function<SceneSettings(const std::string& file, const Scene& scene)> settings;
    Progress progress;
    std::function<void(const std::string& message)> warn;  // a render that went through but may be wrong
};

}  // namespace vkray::render
