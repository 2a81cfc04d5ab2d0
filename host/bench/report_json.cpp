// bench.json: every figure of a BenchResults, for scripts. Keys are snake_case and stable; a figure
// that could not be measured is null, with a "note" saying why where there is one. Images are not
// in the JSON (report.html and images/ have them); their file names are.
#include <cmath>

#include <nlohmann/json.hpp>

#include "bench/bench_json.h"
#include "bench/bench_resume.h"
#include "bench/bench_shard.h"
#include "bench/report.h"
#include "bench/report_tables.h"

namespace vkray::bench {
namespace {

using Json = nlohmann::ordered_json;

// JSON has no infinity or NaN: such a value becomes null rather than an invalid file.
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
Json number(const std::optional<double>& v) { return v ? number(*v) : Json(nullptr); }

Json spread(const Spread& s) { return {{"median", number(s.median)}, {"min", number(s.min)}, {"max", number(s.max)}}; }

Json imageErrorJson(const ImageError& e) {
    return {{"rmse", number(e.rmse)},
            {"psnr_db", number(e.psnr)},
            {"max_error", number(e.maxError)},
            {"primary_hit_mismatch", number(e.primaryMismatch)}};
}

// Where a report's pictures of one scene went: by accelerator ("" for the reference) and role.
class ImageNames {
public:
    ImageNames(const std::vector<ReportImage>& images, size_t scene, bool pixels)
        : images_(images), scene_(scene), pixels_(pixels) {}
    Json of(const std::string& accel) const {
        Json j = Json::object(), pixels = Json::object();
        for (const ReportImage& im : images_) {
            if (im.scene != scene_ || im.accel != accel) continue;
            j[roleName(im.role)] = im.fileName;
            pixels[roleName(im.role)] = pixelsFileName(im.fileName);
        }
        if (pixels_ && !pixels.empty()) j["pixels"] = pixels;
        return j;
    }

private:
    static const char* roleName(ImageRole r) {
        switch (r) {
        case ImageRole::Reference: return "reference";
        case ImageRole::Render: return "render";
        case ImageRole::Difference: return "difference";
        case ImageRole::Heatmap: return "heatmap";
        case ImageRole::PrimaryHeatmap: return "primary_heatmap";
        }
        return "image";
    }
    const std::vector<ReportImage>& images_;
    size_t scene_;
    bool pixels_;
};

Json accelResult(const SceneResult& scene, const AccelResult& a, const ImageNames& names) {
    Json build = Json::array();
    for (const ThreadTiming& t : a.build) build.push_back({{"threads", t.threads}, {"ms", spread(t.ms)}});
    Json stats = Json::object();
    for (const accel::AccelStat& s : a.buildStats) stats[s.key] = {{"value", number(s.value)}, {"unit", s.unit}};
    Json kinds = Json::array();
    for (const RayKindFigures& k : a.rayKinds) {
        Json j = {{"kind", k.kind}, {"rays", k.rays}, {"mrays_per_s", number(k.mraysPerSecond)}};
        if (!k.note.empty()) j["note"] = k.note;
        kinds.push_back(j);
    }
    Json j = {{"accel", a.accel},
            {"kernel", a.kernel},
            {"build", build},
            {"build_on", a.buildOnDevice ? "device" : "cpu"},
            {"build_stats", stats},
            {"structure_bytes", a.structureBytes},
            {"trace_ms", spread(a.traceMs)},
            {"primary_only_ms", spread(a.primaryOnlyMs)},
            {"depth_one_ms", spread(a.depthOneMs)},
            {"embree_interleaved", a.embreeSingleMs ? Json{{"intersect1_ms", spread(*a.embreeSingleMs)},
                                                           {"intersect16_ms", spread(*a.embreePacketMs)},
                                                           {"primary_vs_intersect1", number(primaryVsEmbree(scene, a))}}
                                                     : Json(nullptr)},
            {"primary_vs_bvh", number(primaryVs(scene, a, "bvh"))},
            {"primary_vs_rayquery", number(primaryVs(scene, a, "rayquery"))},
            {"mrays_per_s", number(a.mraysPerSecond)},
            {"ray_kinds", kinds},
            // null: the traversal has no counters (rayquery)
            {"per_ray", !a.traversalCounted ? Json(nullptr)
                                            : Json{{"nodes", number(a.nodesPerRay)},
                                                   {"leaves", number(a.leavesPerRay)},
                                                   {"triangles", number(a.trianglesPerRay)},
                                                   {"restarts", number(a.restartsPerRay)}}},
            {"per_primary_ray", !a.traversalCounted ? Json(nullptr)
                                                    : Json{{"nodes", number(a.primaryNodesPerRay)},
                                                           {"triangles", number(a.primaryTrianglesPerRay)},
                                                           {"lockstep_nodes", number(a.primaryLockstepNodesPerRay)},
                                                           {"simd_lanes", a.simdLanes}}},
            {"capped_rays", a.cappedRays},
            {"error", imageErrorJson(a.error)},
            {"images", names.of(a.accel)}};
    if (const std::string about = accelAbout(a.accel); !about.empty()) j["about"] = about;
    return j;
}

Json errorPoint(const ErrorPoint& p) {
    Json j = {{"label", p.label}, {"group", p.group}, {"accel", p.accel}};
    if (p.delta > 0) j["aac_delta"] = p.delta;
    if (p.maxDepth > 0) j["maxdepth"] = p.maxDepth;
    j["precision"] = p.precision;
    j["build_ms"] = number(p.buildMs);
    j["trace_ms"] = number(p.traceMs);
    j["total_ms"] = number(p.totalMs());
    j["error"] = imageErrorJson(p.error);
    j["pareto"] = p.pareto;
    return j;
}

Json deltaResult(const DeltaResult& d) {
    return {{"aac_delta", d.delta},
            {"aac_epsilon", number(d.epsilon)},
            {"build_ms", spread(d.buildMs)},
            {"trace_ms", spread(d.traceMs)},
            {"total_ms", number(d.buildMs.median + d.traceMs.median)},
            {"nodes_per_ray", number(d.nodesPerRay)},
            {"triangles_per_ray", number(d.trianglesPerRay)},
            {"sah_cost", number(d.sahCost)}};
}

Json embree(const EmbreeResult& e, double rays) {
    if (e.version.empty()) return {{"note", e.note}};
    return {{"version", e.version},
            {"threads", e.threads},
            {"intersect1_ms", spread(e.singleMs)},
            {"intersect16_ms", spread(e.packetMs)},
            {"intersect1_mrays_per_s", number(mraysPerSecond(rays, e.singleMs.median))},
            {"intersect16_mrays_per_s", number(mraysPerSecond(rays, e.packetMs.median))},
            {"agreement_with_reference", number(e.agreement)},
            {"intersect1_samples_ms", e.singleSamples},
            {"intersect16_samples_ms", e.packetSamples}};
}

Json sceneResult(const SceneResult& s, const ImageNames& names) {
    Json accels = Json::array(), points = Json::array(), deltas = Json::array(), configs = Json::array();
    for (const AccelResult& a : s.accels) accels.push_back(accelResult(s, a, names));
    for (const ErrorPoint& p : s.errorPoints) points.push_back(errorPoint(p));
    for (const DeltaResult& d : s.deltas) deltas.push_back(deltaResult(d));
    for (const ConfigurationRun& c : s.configurations) configs.push_back({{"label", c.label}, {"shard", c.shard}});
    Json j = {{"index", s.index},
              {"file", s.file},
              {"name", s.name},
              {"triangles", s.triangles},
              {"width", s.width},
              {"height", s.height},
              {"maxdepth", s.maxDepth},
              {"reference", {{"renderer", "CPU, double precision"},
                             {"accel", s.referenceAccel},
                             {"build_ms", number(s.referenceBuildMs)},
                             {"render_ms", number(s.referenceRenderMs)},
                             {"images", names.of("")}}},
              {"view", s.view},
              {"embree", embree(s.embree, double(s.width) * double(s.height))},
              {"accelerators", accels},
              {"aac_delta_sweep", deltas},
              {"error_vs_time", points},
              {"configurations", configs}};
    if (s.concurrent) {
        const ConcurrentBuild& c = *s.concurrent;
        j["concurrent_build"] = {{"bvh", c.bvhAccel},
                                 {"kd", c.kdAccel},
                                 {"bvh_alone_ms", spread(c.bvhMs)},
                                 {"kd_alone_ms", spread(c.kdMs)},
                                 {"separate_ms", number(c.bvhMs.median + c.kdMs.median)},
                                 {"concurrent_ms", spread(c.concurrentMs)}};
    } else {
        j["concurrent_build"] = nullptr;
    }
    return j;
}

// The 1-minute load averages of a run, null where the system gave none.
Json loadAverage(const std::optional<double>& start, const std::optional<double>& end) {
    return {{"start", number(start)}, {"end", number(end)}};
}

Json shardInfo(const ShardInfo& s) {
    return {{"index", s.shard.index},
            {"count", s.shard.count},
            {"node", s.node},
            {"device", {{"name", s.device}, {"type", s.deviceType}, {"driver", s.driver}, {"vulkan", s.vulkanApi}}},
            {"hardware_threads", s.hardwareThreads},
            {"load_average", loadAverage(s.loadAverageStart, s.loadAverageEnd)},
            {"command_line", s.commandLine},
            {"started_at", s.startedAt},
            {"elapsed_s", number(s.elapsedSeconds)},
            {"configurations", s.configurations},
            {"source", s.source}};
}

}  // namespace

std::string pixelsFileName(const std::string& png) {
    const std::string stem = png.ends_with(".png") ? png.substr(0, png.size() - 4) : png;
    return stem + ".pfm";
}

std::string benchJson(const BenchResults& r) { return benchJson(r, reportImages(r)); }

std::string benchJson(const BenchResults& r, const std::vector<ReportImage>& images) {
    Json scenes = Json::array();
    for (size_t i = 0; i < r.scenes.size(); ++i)
        scenes.push_back(sceneResult(r.scenes[i], ImageNames(images, i, keepsPixels(r))));
    Json shards = Json::array();
    for (const ShardInfo& s : r.shards) shards.push_back(shardInfo(s));
    const Json j = {{"vkray", {{"version", r.vkrayVersion}, {"revision", r.revision}}},
                    {"command_line", r.commandLine},
                    {"started_at", r.startedAt},
                    {"elapsed_s", number(r.elapsedSeconds)},
                    {"device", {{"name", r.device}, {"type", r.deviceType}, {"driver", r.driver}, {"vulkan", r.vulkanApi}}},
                    {"host", {{"hardware_threads", r.hardwareThreads},
                              {"node", r.node},
                              {"load_average", loadAverage(r.loadAverageStart, r.loadAverageEnd)}}},
                    {"settings", settingsJson(r.settings)},
                    {"shard", {{"index", r.shard.index}, {"count", r.shard.count}}},
                    {"configurations", {{"count", r.configurationCount}, {"hash", r.configurationHash}}},
                    {"shards", shards},
                    {"method", {{"repeat", r.repeat},
                                {"warm_up_runs", 1},
                                {"statistic", "median with min-max"},
                                {"gpu_clock", "Vulkan timestamp queries"},
                                {"build_threads", r.threadCounts}}},
                    {"warnings", runWarnings(r)},
                    {"complete", r.complete()},
                    {"failure", r.complete() ? Json(nullptr) : Json(r.failure)},
                    {"missing_scenes", missingScenes(r)},
                    {"scenes", scenes}};
    return j.dump(2) + "\n";
}

}  // namespace vkray::bench
