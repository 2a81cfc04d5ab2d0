// The acceleration structure of a render: built for its spec (accel::buildAccel), or read from a
// structure file (--load-accel), and written to one after its build (--save-accel).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "accel/accel.h"
#include "accel/accel_file.h"
#include "accel/accel_spec.h"
#include "core/phase_log.h"
#include "geometry/tracer.h"
#include "render/render_report.h"
#include "render/scene_hashes.h"
#include "scene/scene.h"

namespace vkray::render {

struct Structure {
    std::unique_ptr<accel::BuiltAccel> built;  // none when read from a file
    std::unique_ptr<geometry::Tracer> tracer;  // CPU renders; walks *built, so is destroyed first
    std::optional<accel::GpuAccelData> data;   // GPU renders, and what a structure file holds
    std::vector<accel::AccelStat> stats;
    double buildMs = 0.0;             // the whole build, the tracer and the arrays included
    std::optional<double> gpuDataMs;  // of buildMs, the arrays in the kernel's layout
};

// What a render needs of a structure: the CPU reference walks a tracer, the GPU reads the arrays.
struct StructureNeeds {
    bool tracer = false;
    bool gpuData = false;
    int threads = 0;                   // builder workers; 0: all cores
    BuildProgress progress = {};       // the build's phases
    std::function<void()> lineDone = {};  // after a build with phases (not brute force's)
};

Structure buildStructure(const Scene& scene, const accel::AccelSpec& spec, const StructureNeeds& needs);

// The structure files of a session: at most one to write after the build, or one to read instead
// of building, whose header is checked against the spec before any scene loads.
class StructureFiles {
public:
    // Refuses both files at once, a file for `brute` (which builds nothing), a file to read for the
    // CPU reference (which walks the builder's own tree) and a path that cannot be written; reads
    // the header of the file to load. Errors name the flags --save-accel and --load-accel.
    StructureFiles(const std::filesystem::path& save, const std::filesystem::path& load, const accel::AccelSpec& spec,
                   bool cpu);

    bool loading() const { return load_.has_value(); }
    // Refuses a file to load that was built for other geometry.
    void checkScene(SceneHashes& hashes);
    // The structure of a render of `scene`: the arrays read from the file to load, or built (and
    // written to the file to save). Fills the structure parts of `report`.
    Structure prepare(const Scene& scene, SceneHashes& hashes, const accel::AccelSpec& spec,
                      const StructureNeeds& needs, RenderReport& report);

private:
    std::filesystem::path save_;
    std::optional<accel::AccelFileReader> load_;  // header read, spec checked; the arrays come later
    double loadMs_ = 0.0;                         // spent on load_ so far
};

}  // namespace vkray::render
