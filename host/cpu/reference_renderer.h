// The CPU reference renderer: the image of docs/shading.md computed independently of the GPU, in
// double precision, so every GPU result can be checked against it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "frame/frame.h"
#include "frame/render_options.h"
#include "geometry/tracer.h"
#include "scene/scene.h"

namespace vkray {

// Called after each finished row with the number of rows finished so far; calls are serialised
// (never two at once) but come from worker threads, with rowsDone increasing by one each time.
using RenderProgress = std::function<void(int rowsDone, int rows)>;

// Renders options.width x options.height pixels with maxdepth options.maxDepth (the caller resolves
// the scene's values and command-line overrides into `options`) on options.threads worker threads
// (0 = all cores). The result is bit-identical whatever the thread count. Uses the brute-force
// tracer.
// Throws vkray::Error when the scene has no camera, the camera or size is unusable, maxDepth < 1,
// or the scene is inconsistent (a material index out of range, a normals list of the wrong size).
Frame renderReference(const Scene& scene, const RenderOptions& options,
                      const RenderProgress& progress = {});

// The same with any tracer built over `scene` (its triangle indices must be the scene's).
Frame renderReference(const Scene& scene, const RenderOptions& options, const geometry::Tracer& tracer,
                      const RenderProgress& progress = {});

// Every ray, hit and shading term of the centre sample of pixel (x, y) of the options.width x
// options.height image (`vkray render --pixel`), as lines of text, in double precision with the
// brute-force tracer, ending with the sample's radiance. Throws as renderReference does, and for a
// pixel outside the image.
std::vector<std::string> tracePixel(const Scene& scene, const RenderOptions& options, int x, int y);

}  // namespace vkray
