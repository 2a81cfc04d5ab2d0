#include "cli/render_printing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>

#include <nlohmann/json.hpp>

#include "render/memory_budget.h"

namespace vkray::cli {
namespace {

// The structure's own build time where it reports one (the builder's clock, phases summed), else
// the time the render command measured around the build (`brute` builds nothing).
double builtMs(const RenderReport& r) {
    for (const accel::AccelStat& st : r.accelStats)
        if (st.key == "build_ms") return st.value;
    return r.buildMs;
}

// Whether the render wrote an image or AOV file (and so has a write time to report).
bool wroteFiles(const RenderReport& r) { return !r.output.empty() || !r.aovs.empty(); }

// A statistic that counts something (nodes, leaves, bytes, a depth, a thread count): a whole number,
// printed as one, never in scientific notation.
bool isCount(const accel::AccelStat& st) {
    return !st.key.ends_with("_ms") && std::floor(st.value) == st.value && std::abs(st.value) < 9.0e15;
}

std::string statText(const accel::AccelStat& st) {
    char text[64];
    if (isCount(st)) std::snprintf(text, sizeof text, "%lld", (long long)st.value);
    else if (st.key.ends_with("_ms")) std::snprintf(text, sizeof text, "%.1f", st.value);
    else std::snprintf(text, sizeof text, "%.4g", st.value);
    return text;
}

// "1" from "Ct=1, Ci=20 ..." for "Ct"; empty when the unit does not name it.
std::string constantIn(const std::string& unit, const std::string& name) {
    const size_t at = unit.find(name + "=");
    if (at == std::string::npos) return "";
    const size_t from = at + name.size() + 1;
    return unit.substr(from, unit.find_first_of(", ;)", from) - from);
}

// What `sah_cost` is measured in, said beside it: the BVHs' (Ci = 1) and the kd-tree's (Ci = 20 by
// default) are both relative to the root's area but weigh a triangle test differently.
std::string sahNote(const std::string& unit) {
    const std::string ct = constantIn(unit, "Ct"), ci = constantIn(unit, "Ci");
    std::string units = ct.empty() || ci.empty() ? "" : ", Ct=" + ct + " a node, Ci=" + ci + " a triangle";
    if (unit.find("eb=") != std::string::npos) units += ", the empty bonus not counted";  // it steers the kd build only
    return "(SAH cost relative to the root's surface area" + units +
           "; a BVH's (Ci=1) and a kd-tree's (Ci=20 unless set) are in different units: compare within a family)";
}

std::string formatMs(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f ms", ms);
    return text;
}

// Compiled-in and left-out kernel features, each sorted by name.
std::pair<std::string, std::string> featureLists(const gpu::ShaderFeatures& features) {
    std::vector<std::pair<std::string, bool>> list = features.list();
    std::sort(list.begin(), list.end());
    std::string on, off;
    for (const auto& [name, enabled] : list) {
        std::string& text = enabled ? on : off;
        text += (text.empty() ? "" : ", ") + name;
    }
    return {on.empty() ? "none" : on, off.empty() ? "none" : off};
}

nlohmann::json gpuJson(const gpu::GpuRenderReport& g) {
    nlohmann::json features = nlohmann::json::object();
    for (const auto& [name, on] : g.features.list()) features[name] = on;
    nlohmann::json j = {{"kernel", g.kernel}, {"tiles", g.tiles}, {"submissions", g.submissions},
                        {"bytes_uploaded", g.bytesUploaded}, {"accel_bytes", g.accelBytes},
                        {"upload_ms", g.uploadMs}, {"pipeline_ms", g.pipelineMs},
                        {"pipelines_created", g.pipelinesCreated}, {"gpu_ms", g.gpuMs},
                        {"dispatch_ms", g.renderMs}, {"rays", g.raysTraced}, {"shadow_rays", g.shadowRays},
                        {"capped_rays", g.cappedRays}, {"features", features},
                        {"resumed", {{"tiles", g.resumedTiles}, {"from_start", g.resumedFromStart},
                                     {"strip_rows", g.resumeRows},
                                     {"dispatches", g.resumeDispatches}}}};
    if (g.driverBuildMs) j["driver_build_ms"] = *g.driverBuildMs;
    if (g.features.countTraversal)
        j["traversal"] = {{"nodes", g.nodesVisited}, {"leaves", g.leavesVisited},
                          {"triangles", g.trianglesTested}, {"restarts", g.restarts},
                          {"lockstep", {{"lanes", g.lockstepLanes}, {"nodes", g.lockstepNodes}}},
                          {"packet_walk", g.packetWalk}, {"idle_steps", g.idleSteps},
                          {"camera_rays", g.cameraRays}};
    return j;
}

void printGpuStats(const gpu::GpuRenderReport& g) {
    const auto [on, off] = featureLists(g.features);
    std::printf("kernel:      compiled in: %s; left out: %s\n", on.c_str(), off.c_str());
    std::printf("gpu:         kernel render_%s, %u tile%s in %u submission%s, %.2f MiB uploaded "
                "(%.2f MiB structure)\n",
                g.kernel.c_str(), g.tiles, g.tiles == 1 ? "" : "s", g.submissions, g.submissions == 1 ? "" : "s", double(g.bytesUploaded) / (1 << 20),
                double(g.accelBytes) / (1 << 20));
    if (g.driverBuildMs)
        std::printf("driver:      built its structure on the device in %.1f ms (GPU timestamps; part of upload)\n",
                    *g.driverBuildMs);
    if (g.resumedTiles > 0)
        std::printf("resumed:     %u tiles beyond the driver's loop budget%s, in strips of %u rows, %u dispatches\n",
                    g.resumedTiles, g.resumedFromStart ? " (from the start)" : "", g.resumeRows,
                    g.resumeDispatches);
    std::printf("rays:        %llu camera and secondary, %llu shadow, %llu capped\n",
                (unsigned long long)g.raysTraced, (unsigned long long)g.shadowRays,
                (unsigned long long)g.cappedRays);
    if (g.features.countTraversal) {
        const double all = double(std::max<uint64_t>(g.raysTraced + g.shadowRays, 1));
        std::printf("traversal:   per ray %.2f nodes, %.2f leaves, %.2f triangle tests, %.3f restarts\n",
                    double(g.nodesVisited) / all, double(g.leavesVisited) / all, double(g.trianglesTested) / all,
                    double(g.restarts) / all);
        if (g.packetWalk && g.lockstepNodes > 0)
            std::printf("packets:     %llu of %llu closest-hit rays walked as packets (%.1f%%: the camera rays; secondary "
                        "and shadow rays walk alone), %.2f node steps a ray, a packet's counted for each lane, lanes' "
                        "use %.1f%%\n",
                        (unsigned long long)g.cameraRays, (unsigned long long)g.raysTraced,
                        100.0 * double(g.cameraRays) / double(std::max<uint64_t>(g.raysTraced, 1)),
                        double(g.lockstepNodes) / all, 100.0 * double(g.nodesVisited) / double(g.lockstepNodes));
        else if (g.lockstepNodes > 0)
            std::printf("simd:        %.2f node steps a ray in lock-step over subgroups of %u, SIMD efficiency %.1f%%\n",
                        double(g.lockstepNodes) / all, g.lockstepLanes,
                        100.0 * double(g.nodesVisited) / double(g.lockstepNodes));
    }
    std::printf("timing:      upload %.1f ms, pipeline %.1f ms%s, gpu %.1f ms (timestamps), dispatch+readback %.1f ms\n",
                g.uploadMs, g.pipelineMs, g.pipelinesCreated == 0 ? " (an earlier scene's)" : "", g.gpuMs, g.renderMs);
}

nlohmann::json memoryJson(const render::MemoryReport& m) {
    nlohmann::json j = {{"host_bytes", m.hostBytes}, {"device_bytes", m.deviceBytes}};
    j["host_limit_bytes"] = m.hostLimit ? nlohmann::json(*m.hostLimit) : nlohmann::json(nullptr);
    if (m.hostLimit) j["host_limit"] = m.hostLimitName;
    j["device_limit_bytes"] = m.deviceLimit ? nlohmann::json(*m.deviceLimit) : nlohmann::json(nullptr);
    return j;
}

// "1.23 GB (of 15.2 GB MemAvailable)"
std::string memoryText(uint64_t bytes, const std::optional<uint64_t>& limit, const std::string& limitName) {
    std::string text = render::formatBytes(bytes);
    if (limit) text += " (of " + render::formatBytes(*limit) + " " + limitName + ")";
    return text;
}

}  // namespace

std::string reportJson(const RenderReport& r) {
    nlohmann::json j;
    j["accel"] = {{"name", r.accel}};
    const bool loaded = r.accelFile && r.accelFile->loaded;
    if (!loaded) j["accel"]["build_ms"] = r.buildMs;  // a loaded structure was not built: no time to give
    if (r.gpuDataMs) j["accel"]["gpu_data_ms"] = *r.gpuDataMs;
    for (const accel::AccelStat& st : r.accelStats) {
        if (isCount(st)) j["accel"][st.key] = int64_t(st.value);
        else j["accel"][st.key] = st.value;
    }
    if (r.accelFile) {
        j["accel"][loaded ? "loaded_from" : "saved_to"] = r.accelFile->path;
        j["accel"][loaded ? "load_ms" : "save_ms"] = r.accelFile->ms;
    }
    if (r.gpu) j["gpu"] = gpuJson(*r.gpu);
    j["memory_estimate"] = memoryJson(r.memory);
    j["scene"] = r.scene;
    j["device"] = r.device;
    j["width"] = r.options.width;
    j["height"] = r.options.height;
    j["maxdepth"] = r.options.maxDepth;
    j["spp"] = r.options.spp;
    if (const auto& w = r.options.window)  // the pixels rendered: columns [x0, x1), rows [y0, y1)
        j["window"] = {{"x0", w->x0}, {"x1", w->x1}, {"y0", w->y0}, {"y1", w->y1}};
    j["triangles"] = r.triangles;
    j["materials"] = r.materials;
    j["lights"] = r.lights;
    j["origin"] = r.origin;
    j["load_ms"] = r.loadMs;
    if (r.deviceMs) j["device_ms"] = *r.deviceMs;
    j["render_ms"] = r.renderMs;
    if (wroteFiles(r)) j["write_ms"] = r.writeMs;
    j["total_ms"] = r.totalMs;
    if (r.buildOnly) j["build_only"] = true;
    if (r.output.empty()) j["output"] = nullptr;  // --pixel without -o, --build-only: no image
    else j["output"] = r.output;
    for (const auto& [name, file] : r.aovs) j["aov"][name] = file;
    return j.dump(2);
}

void printReport(const RenderReport& r, bool stats) {
    if (r.buildOnly) {  // no device, no image: what was built, from what, and where it went
        std::printf("built:       %s structure of %s (%zu triangle%s) in %s (load %s; total %s); nothing rendered\n",
                    r.accel.c_str(), r.scene.c_str(), r.triangles, r.triangles == 1 ? "" : "s", formatMs(r.buildMs).c_str(),
                    formatMs(r.loadMs).c_str(), formatMs(r.totalMs).c_str());
    } else {
        std::printf("device:      %s\n", r.device.c_str());
        std::printf("resolution:  %dx%d, maxdepth %d, %d sample%s a pixel, accel %s\n", r.options.width,
                    r.options.height, r.options.maxDepth, r.options.spp, r.options.spp == 1 ? "" : "s", r.accel.c_str());
        if (const auto& w = r.options.window)
            std::printf("window:      columns %d-%d, rows %d-%d (%dx%d pixels)\n", w->x0, w->x1 - 1, w->y0, w->y1 - 1,
                        w->width(), w->height());
        // The render, and beside it what else the command spent: a big scene's load and build can
        // take longer than its render.
        const std::string structure = r.accelFile && r.accelFile->loaded
                                          ? "structure loaded " + formatMs(r.accelFile->ms)
                                          : "build " + formatMs(r.buildMs);
        std::printf("render time: %s (load %s, %s%s%s; total %s)\n", formatMs(r.renderMs).c_str(),
                    formatMs(r.loadMs).c_str(), structure.c_str(),
                    r.deviceMs && *r.deviceMs >= 0.05 ? (", device start " + formatMs(*r.deviceMs)).c_str() : "",
                    wroteFiles(r) ? (", write " + formatMs(r.writeMs)).c_str() : "", formatMs(r.totalMs).c_str());
    }
    if (!r.output.empty()) std::printf("output:      %s\n", r.output.c_str());
    for (const auto& [name, file] : r.aovs) std::printf("aov %-7s  %s\n", name.c_str(), file.c_str());
    if (r.accelFile)
        std::printf("accel file:  %s %s in %.1f ms\n", r.accelFile->loaded ? "loaded from" : "saved to",
                    r.accelFile->path.c_str(), r.accelFile->ms);
    if (!stats) return;
    std::printf("scene:       %zu triangles, %zu materials, %zu lights (loaded in %.1f ms)\n", r.triangles,
                r.materials, r.lights, r.loadMs);
    if (r.origin != std::array<double, 3>{})
        std::printf("origin:      (%.17g, %.17g, %.17g), positions stored relative to it\n", r.origin[0],
                    r.origin[1], r.origin[2]);
    std::printf("memory:      estimated peak %s host", memoryText(r.memory.hostBytes, r.memory.hostLimit,
                                                                     r.memory.hostLimitName).c_str());
    if (r.memory.deviceBytes > 0)
        std::printf(", %s device", memoryText(r.memory.deviceBytes, r.memory.deviceLimit, "device-local").c_str());
    std::printf("\n");
    if (r.accelFile && r.accelFile->loaded)
        std::printf("accel:       %s, loaded from %s in %.1f ms (not built)\n", r.accel.c_str(),
                    r.accelFile->path.c_str(), r.accelFile->ms);
    else
        std::printf("accel:       %s, built in %.1f ms%s\n", r.accel.c_str(), builtMs(r),
                    r.gpuDataMs ? (", laid out for the kernel in " + formatMs(*r.gpuDataMs)).c_str() : "");
    for (const accel::AccelStat& st : r.accelStats) {
        std::printf("  %-24s %s %s\n", st.key.c_str(), statText(st).c_str(), st.unit.c_str());
        if (st.key == "sah_cost") std::printf("  %-24s %s\n", "", sahNote(st.unit).c_str());
    }
    if (r.gpu) printGpuStats(*r.gpu);
}

namespace {

void printTileProgress(uint32_t done, uint32_t total) {
    std::fprintf(stderr, "\rrendering: tile %u/%u", done, total);
    if (done == total) std::fprintf(stderr, "\r%*s\r", 40, "");
}

void printBuildProgress(const std::string& phase, double fraction) {
    std::fprintf(stderr, "\rbuilding: %-24s %3d%%", phase.c_str(), int(fraction * 100.0 + 0.5));
}

void clearProgressLine() { std::fprintf(stderr, "\r%*s\r", 48, ""); }

void printLoadProgress(const std::string& step) {
    clearProgressLine();
    std::fprintf(stderr, "loading: %s", step.c_str());
}

void printRowProgress(int done, int total) {
    if (done % 16 != 0 && done != total) return;
    std::fprintf(stderr, "\rrendering: row %d/%d", done, total);
    if (done == total) std::fprintf(stderr, "\r%*s\r", 40, "");
}

}  // namespace

void printPixel(const Frame& frame, const RenderReport& report) {
    const glm::vec3 c = frame.color[0], n = frame.normal[0];
    std::printf("pixel %d,%d of %dx%d: colour %.6g %.6g %.6g", frame.x0, frame.y0, report.options.width,
                report.options.height, c.x, c.y, c.z);
    if (frame.primId[0] < 0) std::printf(", no hit");
    else std::printf(", depth %.6g, triangle %d, normal %.4f %.4f %.4f", frame.depth[0], frame.primId[0], n.x, n.y, n.z);
    if (report.gpu && report.options.countTraversal) {  // over every ray of the pixel
        const auto count = [](uint64_t n, const char* one, const char* many) {
            std::printf(", %llu %s", (unsigned long long)n, n == 1 ? one : many);
        };
        count(report.gpu->nodesVisited, "node", "nodes");
        count(report.gpu->leavesVisited, "leaf", "leaves");
        count(report.gpu->trianglesTested, "triangle test", "triangle tests");
    }
    std::printf("\n");
}

render::Progress progressLine() {
    return render::Progress{.load = printLoadProgress,
                            .build = printBuildProgress,
                            .tiles = printTileProgress,
                            .rows = printRowProgress,
                            .lineDone = clearProgressLine};
}

}  // namespace vkray::cli
