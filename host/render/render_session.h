// A render session: the scenes of one `vkray render` call (or of a test), each loaded, checked,
// given its structure (built, or read from a structure file, and saved), rendered on the GPU or by
// the CPU reference, and written with its AOVs. The session holds what its scenes share: the
// structure files, the Vulkan device (opened on a thread while the first scene loads) with its
// kernels' pipelines, and the image files written so far.
//
// Per scene: load; checkRenderable(); the camera of request.view; request.settings(); the output
// paths checked; a file to load checked against the scene; the device opened and the scene checked
// against its limits (gpu::checkSceneFits) and its memory and the host's (render/memory_budget.h,
// also asked while the scene loads), once, before a long build; the structure and, on the
// GPU, the kernel's pipeline on a thread meanwhile; the frame; the files.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "frame/frame.h"
#include "render/device.h"
#include "render/render_report.h"
#include "render/render_request.h"
#include "render/structure.h"

namespace vkray::render {

// What one scene of a session gives back.
struct SceneRender {
    RenderReport report;
    Frame frame;  // empty for request.buildOnly
    // request.tracePixel: every ray, hit and shading term of the centre ray of the frame's first
    // pixel, traced by the CPU reference in double precision with brute force (cpu::tracePixel).
    std::vector<std::string> centreRay;
};

class RenderSession {
public:
    // Checks the structure files against the request (a file to load: its header, before any scene
    // loads) and starts opening the device unless request.cpu or request.buildOnly.
    explicit RenderSession(RenderRequest request);

    // Renders the scene file `sceneFile` and writes its outputs. Throws vkray::Error, among others
    // for an image another scene of the session wrote.
    SceneRender render(const std::string& sceneFile);

private:
    struct Loaded;
    Loaded load(const std::string& sceneFile);
    void openDevice(const Scene& scene, RenderReport& report);
    Frame renderFrame(const Scene& scene, const RenderOptions& options, SceneHashes& hashes, RenderReport& report);
    Frame renderOnDevice(const Scene& scene, const RenderOptions& options, const Structure& structure,
                         RenderReport& report);

    RenderRequest request_;
    StructureFiles files_;
    Device device_;
    std::map<std::filesystem::path, std::string> written_;  // image -> the scene that wrote it
};

}  // namespace vkray::render
