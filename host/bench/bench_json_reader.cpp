// Reading a bench report back (bench_json.h): bench.json into BenchResults, the mirror of
// report_json.cpp, and the pictures it names from images/. Every number comes back as written, so
// writing the results again gives the same figures; JSON null (a figure not measured, or not
// finite) comes back as an empty optional or NaN, which the writer writes as null again.
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bench/bench_json.h"
#include "bench/bench_shard.h"
#include "core/error.h"
#include "image/image_io.h"

namespace fs = std::filesystem;

namespace vkray::bench {
namespace {

using Json = nlohmann::ordered_json;

// Where in the file a value sits, for errors: "scenes[0].accelerators[2].trace_ms".
std::string path(const std::string& where, const std::string& key) { return where.empty() ? key : where + "." + key; }

const Json& at(const Json& j, const std::string& key, const std::string& where) {
    if (!j.is_object() || !j.contains(key)) throw Error("no \"" + path(where, key) + "\"");
    return j[key];
}

double num(const Json& v, const std::string& where) {
    if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!v.is_number()) throw Error("\"" + where + "\" is not a number");
    return v.get<double>();
}
double num(const Json& j, const std::string& key, const std::string& where) { return num(at(j, key, where), path(where, key)); }

std::optional<double> optNum(const Json& j, const std::string& key, const std::string& where) {
    const Json& v = at(j, key, where);
    if (v.is_null()) return std::nullopt;
    return num(v, path(where, key));
}

template <typename T>
T get(const Json& j, const std::string& key, const std::string& where) {
    const Json& v = at(j, key, where);
    try {
        return v.get<T>();
    } catch (const nlohmann::json::exception&) {
        throw Error("\"" + path(where, key) + "\" is not what a bench run writes");
    }
}

std::string str(const Json& j, const std::string& key, const std::string& where) { return get<std::string>(j, key, where); }

const Json& array(const Json& j, const std::string& key, const std::string& where) {
    const Json& v = at(j, key, where);
    if (!v.is_array()) throw Error("\"" + path(where, key) + "\" is not an array");
    return v;
}

std::string item(const std::string& where, const std::string& key, size_t i) {
    return path(where, key) + "[" + std::to_string(i) + "]";
}

Spread spread(const Json& j, const std::string& key, const std::string& where) {
    const Json& s = at(j, key, where);
    const std::string w = path(where, key);
    return {num(s, "median", w), num(s, "min", w), num(s, "max", w)};
}

ImageError readImageError(const Json& j, const std::string& where) {
    const Json& e = at(j, "error", where);
    const std::string w = path(where, "error");
    return {num(e, "rmse", w), optNum(e, "psnr_db", w), num(e, "max_error", w), num(e, "primary_hit_mismatch", w)};
}

// The pictures' pixels, read back from the PFMs under images/ that bench.json names ("images":
// {"pixels": {ROLE: FILE}}); a report without them gives no pictures.
class Pictures {
public:
    explicit Pictures(fs::path dir) : dir_(std::move(dir)) {}
    Image image(const Json& names, const char* role) const {
        if (!names.is_object() || !names.contains("pixels")) return {};
        const Json& pixels = names["pixels"];
        if (!pixels.is_object() || !pixels.contains(role) || !pixels[role].is_string()) return {};
        return readImage(dir_ / pixels[role].get<std::string>());
    }
    std::vector<uint32_t> counts(const Json& names, const char* role) const {
        const Image im = image(names, role);
        std::vector<uint32_t> out;
        if (im.channels != 1) return out;
        for (float v : im.data) out.push_back(std::isfinite(v) && v > 0.0f ? uint32_t(v) : 0u);
        return out;
    }

private:
    fs::path dir_;
};

// The traversal counters of an accelerator's entry (per_ray, per_primary_ray).
void readCounters(const Json& j, const std::string& w, AccelResult& a) {
    const Json& perRay = at(j, "per_ray", w);
    const std::string wp = path(w, "per_ray");
    a.nodesPerRay = num(perRay, "nodes", wp);
    a.leavesPerRay = num(perRay, "leaves", wp);
    a.trianglesPerRay = num(perRay, "triangles", wp);
    a.restartsPerRay = num(perRay, "restarts", wp);
    const Json& primary = at(j, "per_primary_ray", w);
    a.primaryNodesPerRay = num(primary, "nodes", path(w, "per_primary_ray"));
    a.primaryTrianglesPerRay = num(primary, "triangles", path(w, "per_primary_ray"));
    if (primary.contains("lockstep_nodes")) {  // reports from before they were measured lack them
        a.primaryLockstepNodesPerRay = num(primary, "lockstep_nodes", path(w, "per_primary_ray"));
        a.simdLanes = get<uint32_t>(primary, "simd_lanes", path(w, "per_primary_ray"));
    }
}

AccelResult accelResult(const Json& j, const std::string& w, const Pictures& pictures) {
    AccelResult a;
    a.accel = str(j, "accel", w);
    a.kernel = str(j, "kernel", w);
    const Json& build = array(j, "build", w);
    for (size_t i = 0; i < build.size(); ++i)
        a.build.push_back({get<int>(build[i], "threads", item(w, "build", i)), spread(build[i], "ms", item(w, "build", i))});
    if (j.contains("build_on")) {  // reports from before the driver's build on the device lack it: CPU
        const std::string on = str(j, "build_on", w);
        if (on != "cpu" && on != "device")
            throw Error("\"" + path(w, "build_on") + "\": \"" + on + "\", expected \"cpu\" or \"device\"");
        a.buildOnDevice = on == "device";
    }
    for (const auto& [key, s] : at(j, "build_stats", w).items())
        a.buildStats.push_back({key, num(s, "value", path(w, key)), str(s, "unit", path(w, key))});
    a.structureBytes = get<uint64_t>(j, "structure_bytes", w);
    a.traceMs = spread(j, "trace_ms", w);
    a.primaryOnlyMs = spread(j, "primary_only_ms", w);
    a.depthOneMs = spread(j, "depth_one_ms", w);
    if (const Json& e = at(j, "embree_interleaved", w); !e.is_null()) {
        a.embreeSingleMs = spread(e, "intersect1_ms", path(w, "embree_interleaved"));
        a.embreePacketMs = spread(e, "intersect16_ms", path(w, "embree_interleaved"));
    }
    a.mraysPerSecond = num(j, "mrays_per_s", w);
    const Json& kinds = array(j, "ray_kinds", w);
    for (size_t i = 0; i < kinds.size(); ++i) {
        const std::string wk = item(w, "ray_kinds", i);
        a.rayKinds.push_back({str(kinds[i], "kind", wk), get<uint64_t>(kinds[i], "rays", wk),
                              optNum(kinds[i], "mrays_per_s", wk),
                              kinds[i].contains("note") ? str(kinds[i], "note", wk) : ""});
    }
    a.traversalCounted = !at(j, "per_ray", w).is_null();  // null: a traversal without counters
    if (a.traversalCounted) readCounters(j, w, a);
    a.cappedRays = get<uint64_t>(j, "capped_rays", w);
    a.error = readImageError(j, w);
    const Json names = j.contains("images") ? j["images"] : Json::object();
    a.image = pictures.image(names, "render");
    a.diff = pictures.image(names, "difference");
    a.nodesPerPixel = pictures.counts(names, "heatmap");
    a.primaryNodesPerPixel = pictures.counts(names, "primary_heatmap");
    return a;
}

ErrorPoint errorPoint(const Json& j, const std::string& w) {
    ErrorPoint p;
    p.label = str(j, "label", w);
    p.group = str(j, "group", w);
    p.accel = str(j, "accel", w);
    p.delta = j.contains("aac_delta") ? get<int>(j, "aac_delta", w) : 0;
    p.maxDepth = j.contains("maxdepth") ? get<int>(j, "maxdepth", w) : 0;
    p.precision = str(j, "precision", w);
    p.buildMs = num(j, "build_ms", w);
    p.traceMs = num(j, "trace_ms", w);
    p.error = readImageError(j, w);
    p.pareto = get<bool>(j, "pareto", w);
    return p;
}

DeltaResult deltaResult(const Json& j, const std::string& w) {
    DeltaResult d;
    d.delta = get<int>(j, "aac_delta", w);
    d.epsilon = num(j, "aac_epsilon", w);
    d.buildMs = spread(j, "build_ms", w);
    d.traceMs = spread(j, "trace_ms", w);
    d.nodesPerRay = num(j, "nodes_per_ray", w);
    d.trianglesPerRay = num(j, "triangles_per_ray", w);
    d.sahCost = num(j, "sah_cost", w);
    return d;
}

EmbreeResult embree(const Json& j, const std::string& w) {
    EmbreeResult e;
    if (!j.contains("version")) {
        e.note = j.contains("note") ? str(j, "note", w) : "";
        return e;
    }
    e.version = str(j, "version", w);
    e.threads = get<int>(j, "threads", w);
    e.singleMs = spread(j, "intersect1_ms", w);
    e.packetMs = spread(j, "intersect16_ms", w);
    e.agreement = num(j, "agreement_with_reference", w);
    e.singleSamples = get<std::vector<double>>(j, "intersect1_samples_ms", w);
    e.packetSamples = get<std::vector<double>>(j, "intersect16_samples_ms", w);
    return e;
}

std::optional<ConcurrentBuild> concurrent(const Json& j, const std::string& w) {
    if (j.is_null()) return std::nullopt;
    return ConcurrentBuild{str(j, "bvh", w), str(j, "kd", w), spread(j, "bvh_alone_ms", w), spread(j, "kd_alone_ms", w),
                           spread(j, "concurrent_ms", w)};
}

SceneResult sceneResult(const Json& j, const std::string& w, const Pictures& pictures) {
    SceneResult s;
    s.index = get<int>(j, "index", w);
    s.file = str(j, "file", w);
    s.name = str(j, "name", w);
    s.view = str(j, "view", w);
    s.triangles = get<uint64_t>(j, "triangles", w);
    s.width = get<int>(j, "width", w);
    s.height = get<int>(j, "height", w);
    s.maxDepth = get<int>(j, "maxdepth", w);
    const Json& ref = at(j, "reference", w);
    s.referenceAccel = str(ref, "accel", path(w, "reference"));
    s.referenceBuildMs = num(ref, "build_ms", path(w, "reference"));
    s.referenceRenderMs = num(ref, "render_ms", path(w, "reference"));
    s.reference = pictures.image(ref.contains("images") ? ref["images"] : Json::object(), "reference");
    s.embree = embree(at(j, "embree", w), path(w, "embree"));
    const Json& accels = array(j, "accelerators", w);
    for (size_t i = 0; i < accels.size(); ++i) s.accels.push_back(accelResult(accels[i], item(w, "accelerators", i), pictures));
    const Json& deltas = array(j, "aac_delta_sweep", w);
    for (size_t i = 0; i < deltas.size(); ++i) s.deltas.push_back(deltaResult(deltas[i], item(w, "aac_delta_sweep", i)));
    const Json& points = array(j, "error_vs_time", w);
    for (size_t i = 0; i < points.size(); ++i) s.errorPoints.push_back(errorPoint(points[i], item(w, "error_vs_time", i)));
    s.concurrent = concurrent(at(j, "concurrent_build", w), path(w, "concurrent_build"));
    const Json& configs = array(j, "configurations", w);
    for (size_t i = 0; i < configs.size(); ++i)
        s.configurations.push_back({str(configs[i], "label", item(w, "configurations", i)),
                                    get<int>(configs[i], "shard", item(w, "configurations", i))});
    return s;
}

// "load_average": {"start", "end"}, absent from reports written before it was recorded.
void loadAverage(const Json& j, const std::string& w, std::optional<double>& start, std::optional<double>& end) {
    if (!j.contains("load_average")) return;
    const Json& l = at(j, "load_average", w);
    start = optNum(l, "start", path(w, "load_average"));
    end = optNum(l, "end", path(w, "load_average"));
}

ShardInfo shardInfo(const Json& j, const std::string& w) {
    ShardInfo s;
    s.shard = {get<int>(j, "index", w), get<int>(j, "count", w)};
    s.node = str(j, "node", w);
    const Json& d = at(j, "device", w);
    s.device = str(d, "name", w);
    s.deviceType = str(d, "type", w);
    s.driver = str(d, "driver", w);
    s.vulkanApi = str(d, "vulkan", w);
    s.hardwareThreads = get<int>(j, "hardware_threads", w);
    loadAverage(j, w, s.loadAverageStart, s.loadAverageEnd);
    s.commandLine = str(j, "command_line", w);
    s.startedAt = str(j, "started_at", w);
    s.elapsedSeconds = num(j, "elapsed_s", w);
    s.configurations = get<size_t>(j, "configurations", w);
    s.source = str(j, "source", w);
    return s;
}

BenchResults benchResults(const Json& j, const Pictures& pictures) {
    BenchResults r;
    r.vkrayVersion = str(at(j, "vkray", ""), "version", "vkray");
    r.revision = str(at(j, "vkray", ""), "revision", "vkray");
    r.commandLine = str(j, "command_line", "");
    r.startedAt = str(j, "started_at", "");
    r.elapsedSeconds = num(j, "elapsed_s", "");
    const Json& d = at(j, "device", "");
    r.device = str(d, "name", "device");
    r.deviceType = str(d, "type", "device");
    r.driver = str(d, "driver", "device");
    r.vulkanApi = str(d, "vulkan", "device");
    r.hardwareThreads = get<int>(at(j, "host", ""), "hardware_threads", "host");
    r.node = str(at(j, "host", ""), "node", "host");
    loadAverage(at(j, "host", ""), "host", r.loadAverageStart, r.loadAverageEnd);
    const Json& method = at(j, "method", "");
    r.repeat = get<int>(method, "repeat", "method");
    r.threadCounts = get<std::vector<int>>(method, "build_threads", "method");
    r.settings = settingsFromJson(at(j, "settings", ""));
    r.shard = {get<int>(at(j, "shard", ""), "index", "shard"), get<int>(at(j, "shard", ""), "count", "shard")};
    r.configurationCount = get<size_t>(at(j, "configurations", ""), "count", "configurations");
    r.configurationHash = str(at(j, "configurations", ""), "hash", "configurations");
    const Json& shards = array(j, "shards", "");
    for (size_t i = 0; i < shards.size(); ++i) r.shards.push_back(shardInfo(shards[i], item("", "shards", i)));
    const Json& scenes = array(j, "scenes", "");
    for (size_t i = 0; i < scenes.size(); ++i) r.scenes.push_back(sceneResult(scenes[i], item("", "scenes", i), pictures));
    // "complete" and "failure" are absent from reports written before runs saved partial results.
    if (j.contains("complete") && !get<bool>(j, "complete", "")) {
        r.failure = at(j, "failure", "").is_string() ? str(j, "failure", "") : "";
        if (r.failure.empty()) r.failure = kStillRunning;
    }
    return r;
}

}  // namespace

BenchResults readBenchReport(const fs::path& dir) {
    const fs::path file = dir / "bench.json";
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Error(FileLoc{file.string()}, fs::exists(file) ? "cannot be read" : "no such file");
    std::stringstream text;
    text << in.rdbuf();
    Json j;
    try {
        j = Json::parse(text.str());
    } catch (const nlohmann::json::parse_error& e) {
        throw Error(FileLoc{file.string()}, "not JSON (at byte " + std::to_string(e.byte) + ")");
    }
    try {
        return benchResults(j, Pictures(dir / "images"));
    } catch (const Error& e) {
        if (e.hasLocation()) throw;  // an image file names itself
        throw Error(FileLoc{file.string()}, e.what());
    }
}

}  // namespace vkray::bench
