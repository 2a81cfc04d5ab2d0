#include "render/structure.h"

#include <string>
#include <utility>

#include "core/error.h"
#include "core/timing.h"

namespace vkray::render {

Structure buildStructure(const Scene& scene, const accel::AccelSpec& spec, const StructureNeeds& needs) {
    Structure s;
    const Clock::time_point t0 = Clock::now();
    s.built = accel::buildAccel(scene, spec, accel::BuildOptions{.threads = needs.threads, .progress = needs.progress});
    if (needs.tracer) s.tracer = s.built->makeTracer(scene);
    const bool nothingBuilt = spec.family == accel::Family::Brute || spec.family == accel::Family::Driver;
    if (needs.lineDone && !nothingBuilt) needs.lineDone();
    s.stats = s.built->stats();
    // Timed apart too: laying the arrays out for the kernel copies the whole structure.
    if (needs.gpuData) {
        const Clock::time_point t1 = Clock::now();
        s.data = s.built->gpuData();
        s.gpuDataMs = msSince(t1);
    }
    s.buildMs = msSince(t0);
    return s;
}

StructureFiles::StructureFiles(const std::filesystem::path& save, const std::filesystem::path& load,
                               const accel::AccelSpec& spec, bool cpu) {
    if (!save.empty() && !load.empty())
        throw Error("--save-accel and --load-accel: give one (a loaded structure is already in its file)");
    const bool brute = spec.family == accel::Family::Brute;
    const bool driver = spec.family == accel::Family::Driver;
    // The driver's structure lives on the device only, built again for each render.
    if (driver && cpu)
        throw Error("--accel rayquery is the device driver's own ray tracing: it has no CPU traversal (drop --cpu, "
                    "or give another --accel)");
    if (driver && (!save.empty() || !load.empty()))
        throw Error(std::string(!save.empty() ? "--save-accel" : "--load-accel") +
                    ": --accel rayquery's structure is built by the driver on the device for each render; "
                    "there is no file of it");
    if (!save.empty()) {
        if (brute) throw Error("--save-accel: --accel brute builds no structure to save");
        accel::checkAccelFileTarget(save);
        save_ = save;
    }
    if (!load.empty()) {
        if (brute) throw Error("--load-accel: --accel brute uses no structure to load");
        // The file holds only what the GPU kernel reads; the CPU renderer walks the builder's own
        // tree. Refusing says so, where rebuilding silently would spend the time the flag was to save.
        if (cpu)
            throw Error("--load-accel " + load.string() + ": the file holds the GPU's arrays only; --cpu "
                        "builds its own structure (drop --load-accel)");
        const Clock::time_point t0 = Clock::now();
        load_.emplace(load);
        load_->checkSpec(spec);
        loadMs_ = msSince(t0);
    }
}

void StructureFiles::checkScene(SceneHashes& hashes) {
    if (!load_) return;
    const Clock::time_point t0 = Clock::now();
    load_->checkScene(hashes.geometry());
    loadMs_ += msSince(t0);
}

Structure StructureFiles::prepare(const Scene& scene, SceneHashes& hashes, const accel::AccelSpec& spec,
                                  const StructureNeeds& needs, RenderReport& report) {
    if (load_) {
        const Clock::time_point t0 = Clock::now();
        accel::LoadedAccel loaded = load_->readArrays();
        report.accelFile = AccelFileReport{.path = load_->path().string(), .loaded = true, .ms = loadMs_ + msSince(t0)};
        report.accelStats = std::move(loaded.stats);
        Structure s;
        s.data = std::move(loaded.data);
        return s;
    }
    StructureNeeds build = needs;
    build.gpuData = needs.gpuData || !save_.empty();
    Structure s = buildStructure(scene, spec, build);
    report.accelStats = s.stats;
    report.gpuDataMs = s.gpuDataMs;
    report.buildMs = s.buildMs;
    if (!save_.empty()) {
        const Clock::time_point t0 = Clock::now();
        accel::saveAccelFile(save_, spec, hashes.geometry(), *s.data, report.accelStats);
        report.accelFile = AccelFileReport{.path = save_.string(), .loaded = false, .ms = msSince(t0)};
    }
    return s;
}

}  // namespace vkray::render
