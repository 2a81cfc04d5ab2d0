// The configuration list of a bench run and its shards (bench_shard.h).
#include "bench/bench_shard.h"

#include <cstdint>
#include <cstdio>
#include <optional>

#include "accel/accel.h"
#include "core/error.h"
#include "core/hash64.h"
#include "scene/text_input.h"

namespace vkray::bench {
namespace {

using Json = nlohmann::ordered_json;

// The first BVH and the first kd-tree of the accelerators: the pair the concurrent build times.
std::optional<std::string> concurrentLabel(const std::vector<std::string>& accels) {
    std::optional<std::string> bvh, kd;
    for (const std::string& name : accels) {
        const accel::AccelSpec spec = accel::resolveAccel(name);
        if (spec.family == accel::Family::Bvh && !bvh) bvh = spec.name;
        if (spec.family == accel::Family::Kd && !kd) kd = spec.name;
    }
    if (!bvh || !kd) return std::nullopt;
    return "concurrent " + *bvh + "+" + *kd;
}

template <typename T>
T field(const Json& j, const char* key) {
    if (!j.contains(key)) throw Error(std::string("settings: no \"") + key + "\"");
    try {
        return j.at(key).get<T>();
    } catch (const nlohmann::json::exception&) {
        throw Error(std::string("settings: \"") + key + "\" is not what a bench run writes");
    }
}

}  // namespace

BenchSettings benchSettings(const BenchOptions& o) {
    BenchSettings s;
    s.scenes = o.scenes;
    s.accels = o.accels;
    s.width = o.width;
    s.height = o.height;
    s.view = o.view;
    s.repeat = o.repeat;
    s.threads = o.threads.empty() ? defaultThreadCounts() : o.threads;
    s.deltas = o.deltas;
    s.maxDepths = o.maxDepths;
    s.maxDepthSweep = o.maxDepthSweep;
    return s;
}

std::vector<Configuration> configurationList(const BenchSettings& s) {
    std::vector<Configuration> list;
    const std::optional<std::string> concurrent = concurrentLabel(s.accels);
    for (size_t i = 0; i < s.scenes.size(); ++i) {
        const int scene = int(i);
        using Kind = Configuration::Kind;
        list.push_back({scene, "reference", Kind::Reference});
        for (const std::string& a : s.accels) list.push_back({scene, "accel " + a, Kind::Accel, a});
        if (concurrent) list.push_back({scene, *concurrent, Kind::Concurrent});
        for (int d : s.deltas) list.push_back({scene, "aac-delta " + std::to_string(d), Kind::Delta, "", d});
        if (s.maxDepthSweep) list.push_back({scene, "maxdepth-sweep", Kind::MaxDepthSweep});
    }
    return list;
}

std::string configurationHash(const std::vector<Configuration>& list) {
    std::string text;
    for (const Configuration& c : list) text += std::to_string(c.scene) + "\t" + c.label + "\n";
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash64(text.data(), text.size())));
    return hex;
}

ShardSpec parseShard(const std::string& text, const std::string& option) {
    const std::optional<IndexOfCount> p = parseIndexOfCount(text);
    if (!p || p->count < 1 || p->count > 10000 || p->index >= p->count)
        throw Error(option + " " + text + ": expected I/N with 0 <= I < N, e.g. 0/4");
    return {p->index, p->count};
}

std::string shardText(const ShardSpec& s) { return std::to_string(s.index) + "/" + std::to_string(s.count); }

std::vector<SceneWork> shardWork(const BenchSettings& settings, const ShardSpec& shard) {
    std::vector<SceneWork> work(settings.scenes.size());
    const std::vector<Configuration> list = configurationList(settings);
    for (size_t k = 0; k < list.size(); ++k) {
        if (!inShard(k, shard)) continue;
        const Configuration& c = list[k];
        SceneWork& w = work[size_t(c.scene)];
        w.labels.push_back(c.label);
        switch (c.kind) {
            case Configuration::Kind::Reference: w.reference = true; break;
            case Configuration::Kind::Accel: w.accels.push_back(c.accel); break;
            case Configuration::Kind::Concurrent: w.concurrent = true; break;
            case Configuration::Kind::Delta: w.deltas.push_back(c.delta); break;
            case Configuration::Kind::MaxDepthSweep: w.maxDepthSweep = true; break;
        }
    }
    return work;
}

Json settingsJson(const BenchSettings& s) {
    return {{"scenes", s.scenes},
            {"accels", s.accels},
            {"width", s.width},
            {"height", s.height},
            {"view", s.view},
            {"repeat", s.repeat},
            {"build_threads", s.threads},
            {"aac_deltas", s.deltas},
            {"maxdepth_sweep", s.maxDepthSweep},
            {"maxdepths", s.maxDepths}};
}

BenchSettings settingsFromJson(const Json& j) {
    if (!j.is_object()) throw Error("settings: not an object");
    BenchSettings s;
    s.scenes = field<std::vector<std::string>>(j, "scenes");
    s.accels = field<std::vector<std::string>>(j, "accels");
    s.width = field<int>(j, "width");
    s.height = field<int>(j, "height");
    s.view = field<std::string>(j, "view");
    s.repeat = field<int>(j, "repeat");
    s.threads = field<std::vector<int>>(j, "build_threads");
    s.deltas = field<std::vector<int>>(j, "aac_deltas");
    s.maxDepthSweep = field<bool>(j, "maxdepth_sweep");
    s.maxDepths = field<std::vector<int>>(j, "maxdepths");
    for (const std::string& a : s.accels) accel::resolveAccel(a);  // a name this vkray knows
    return s;
}

std::optional<std::string> settingsDifference(const BenchSettings& mine, const BenchSettings& theirs) {
    const Json a = settingsJson(mine), b = settingsJson(theirs);
    for (const auto& [key, value] : a.items())
        if (!b.contains(key) || b[key] != value)
            return key + " is " + value.dump() + " here, " + (b.contains(key) ? b[key].dump() : "missing");
    return std::nullopt;
}

}  // namespace vkray::bench
