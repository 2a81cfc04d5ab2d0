#include "render/outputs.h"

#include <cstdio>

#include "image/image_io.h"
#include "scene/camera.h"
#include "vkray_revision.h"  // generated at build time by scripts/revision.cmake

namespace vkray::render {

bool anyExr(const std::filesystem::path& image, const std::map<std::string, std::string>& aovs) {
    bool exr = !image.empty() && imageFormatForPath(image) == ImageFormat::Exr;
    for (const auto& [name, file] : aovs) exr = exr || imageFormatForPath(file) == ImageFormat::Exr;
    return exr;
}

// The same scene is its file's bytes and its geometry (which includes the meshes); the same
// settings are everything that changes a pixel.
ImageMeta outputMeta(const std::string& sceneFile, const Scene& scene, SceneHashes& hashes,
                     const RenderOptions& options, const RenderReport& report,
                     const std::optional<IndexOfCount>& tile) {
    const PixelWindow w = options.pixels();
    ImageMeta meta;
    meta.displayWidth = options.width;
    meta.displayHeight = options.height;
    meta.x0 = w.x0;
    meta.y0 = w.y0;
    char geometry[24];
    std::snprintf(geometry, sizeof geometry, "%016llx", (unsigned long long)hashes.geometry().hash);
    const Camera& c = scene.camera;
    char settings[512];
    std::snprintf(settings, sizeof settings,
                  "size %dx%d spp %d maxdepth %d accel %s camera %.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g "
                  "background %.9g,%.9g,%.9g device %s",
                  options.width, options.height, options.spp, options.maxDepth, report.accel.c_str(), c.eye.x, c.eye.y,
                  c.eye.z, c.center.x, c.center.y, c.center.z, c.up.x, c.up.y, c.up.z, c.fovyDegrees, scene.background.x,
                  scene.background.y, scene.background.z, report.device.c_str());
    meta.attributes["vkray:version"] = std::string(VKRAY_VERSION) + " (revision " + VKRAY_REVISION + ")";
    meta.attributes["vkray:scene"] = std::filesystem::path(sceneFile).filename().string() + " file " +
                                     hashes.fileHash() + " geometry " + geometry;
    meta.attributes["vkray:settings"] = settings;
    if (tile) meta.attributes["vkray:tile"] = std::to_string(tile->index) + "/" + std::to_string(tile->count);
    return meta;
}

void writeOutputs(const Frame& frame, const std::filesystem::path& image, const Encoding& encoding,
                  const std::map<std::string, std::string>& aovs, const ImageMeta& meta) {
    if (!image.empty()) writeColorImage(image, frame.width, frame.height, frame.color, meta, encoding);
    for (const auto& [name, file] : aovs) writeAov(file, frame, name, meta);
}

}  // namespace vkray::render
