// A render's files: the colour image and the AOVs, and what an EXR among them records of its
// render (image/image_meta.h): where its window lies in the whole image, and the scene, settings
// and vkray that made it, so that `vkray assemble` can check that tiles belong together.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "frame/frame.h"
#include "frame/render_options.h"
#include "image/image_meta.h"
#include "render/render_report.h"
#include "render/scene_hashes.h"
#include "scene/scene.h"
#include "scene/text_input.h"

namespace vkray::render {

// Whether the colour image `image` (empty: none) or an AOV file is an EXR, the one format that
// keeps the metadata.
bool anyExr(const std::filesystem::path& image, const std::map<std::string, std::string>& aovs);

// The metadata of the outputs of a render of `scene` (file `sceneFile`, its hashes in `hashes`) with
// `options` on report.device with report.accel; `tile`: the band of a tiled render.
ImageMeta outputMeta(const std::string& sceneFile, const Scene& scene, SceneHashes& hashes,
                     const RenderOptions& options, const RenderReport& report,
                     const std::optional<IndexOfCount>& tile);

// Writes the colour image (unless `image` is empty) and every AOV of `aovs` (name -> file).
void writeOutputs(const Frame& frame, const std::filesystem::path& image, const Encoding& encoding,
                  const std::map<std::string, std::string>& aovs, const ImageMeta& meta);

}  // namespace vkray::render
