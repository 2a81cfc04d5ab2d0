// bench.json: every figure of a BenchResults, for scripts. Keys are snake_case and stable; a figure
// that could not be measured is null, with a "note" saying why where there is one. Images are not
// in the JSON (report.html and images/ have them); their sizes are.
#include <cmath>

#include <nlohmann/json.hpp>

#include "bench/report.h"

namespace vkray::bench {
namespace {

using Json = nlohmann::ordered_json;

// JSON has no infinity or NaN: such a value becomes null rather than an invalid file.
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
Json number(const std::optional<double>& v) { return v ? number(*v) : Json(nullptr); }

Json spread(const Spread& s) { return {{"median", number(s.median)}, {"min", number(s.min)}, {"max", number(s.max)}}; }

Json imageError(const ImageError& e) {
    return {{"rmse", number(e.rmse)},
            {"psnr_db", number(e.psnr)},
            {"max_error", number(e.maxError)},
            {"primary_hit_mismatch", number(e.primaryMismatch)}};
}

Json accelResult(const AccelResult& a) {
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
    return {{"accel", a.accel},
            {"kernel", a.kernel},
            {"build", build},
            {"build_stats", stats},
            {"structure_bytes", a.structureBytes},
            {"trace_ms", spread(a.traceMs)},
            {"primary_only_ms", spread(a.primaryOnlyMs)},
            {"depth_one_ms", spread(a.depthOneMs)},
            {"embree_interleaved", a.embreeSingleMs ? Json{{"intersect1_ms", spread(*a.embreeSingleMs)},
                                                           {"intersect16_ms", spread(*a.embreePacketMs)},
                                                           {"primary_vs_intersect1", number(a.primaryVsEmbree())}}
                                                     : Json(nullptr)},
            {"mrays_per_s", number(a.mraysPerSecond)},
            {"ray_kinds", kinds},
            {"per_ray", {{"nodes", number(a.nodesPerRay)},
                         {"leaves", number(a.leavesPerRay)},
                         {"triangles", number(a.trianglesPerRay)},
                         {"restarts", number(a.restartsPerRay)}}},
            {"per_primary_ray", {{"nodes", number(a.primaryNodesPerRay)}, {"triangles", number(a.primaryTrianglesPerRay)}}},
            {"capped_rays", a.cappedRays},
            {"error", imageError(a.error)}};
}

Json errorPoint(const ErrorPoint& p) {
    Json j = {{"label", p.label}, {"group", p.group}, {"accel", p.accel}};
    if (p.delta > 0) j["aac_delta"] = p.delta;
    if (p.maxDepth > 0) j["maxdepth"] = p.maxDepth;
    j["precision"] = p.precision;
    j["build_ms"] = number(p.buildMs);
    j["trace_ms"] = number(p.traceMs);
    j["total_ms"] = number(p.totalMs());
    j["error"] = imageError(p.error);
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
            {"agreement_with_reference", number(e.agreement)}};
}

Json sceneResult(const SceneResult& s) {
    Json accels = Json::array(), points = Json::array(), deltas = Json::array();
    for (const AccelResult& a : s.accels) accels.push_back(accelResult(a));
    for (const ErrorPoint& p : s.errorPoints) points.push_back(errorPoint(p));
    for (const DeltaResult& d : s.deltas) deltas.push_back(deltaResult(d));
    Json j = {{"file", s.file},
              {"name", s.name},
              {"triangles", s.triangles},
              {"width", s.width},
              {"height", s.height},
              {"maxdepth", s.maxDepth},
              {"reference", {{"renderer", "CPU, double precision"},
                             {"accel", s.referenceAccel},
                             {"build_ms", number(s.referenceBuildMs)},
                             {"render_ms", number(s.referenceRenderMs)}}},
              {"view", s.view},
              {"embree", embree(s.embree, double(s.width) * double(s.height))},
              {"accelerators", accels},
              {"aac_delta_sweep", deltas},
              {"error_vs_time", points}};
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

}  // namespace

std::string benchJson(const BenchResults& r) {
    Json scenes = Json::array();
    for (const SceneResult& s : r.scenes) scenes.push_back(sceneResult(s));
    const Json j = {{"vkray", {{"version", r.vkrayVersion}, {"revision", r.revision}}},
                    {"command_line", r.commandLine},
                    {"started_at", r.startedAt},
                    {"elapsed_s", number(r.elapsedSeconds)},
                    {"device", {{"name", r.device}, {"type", r.deviceType}, {"driver", r.driver}, {"vulkan", r.vulkanApi}}},
                    {"host", {{"hardware_threads", r.hardwareThreads}}},
                    {"method", {{"repeat", r.repeat},
                                {"warm_up_runs", 1},
                                {"statistic", "median with min-max"},
                                {"gpu_clock", "Vulkan timestamp queries"},
                                {"build_threads", r.threadCounts}}},
                    {"scenes", scenes}};
    return j.dump(2) + "\n";
}

}  // namespace vkray::bench
