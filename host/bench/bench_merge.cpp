// Merging the shards of a bench run (bench_merge.h).
#include "bench/bench_merge.h"

#include <algorithm>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "bench/bench_json.h"
#include "bench/bench_resume.h"
#include "bench/bench_shard.h"
#include "bench/report.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace vkray::bench {
namespace {

struct Shard {
    fs::path file;  // DIR/bench.json, for errors
    BenchResults results;
};

Error shardError(const Shard& s, const std::string& what) { return Error(FileLoc{s.file.string()}, what); }

// Every shard of one run, each once and none missing.
void checkShards(const std::vector<Shard>& shards) {
    const Shard& first = shards.front();
    const BenchResults& f = first.results;
    std::map<int, const Shard*> seen;
    for (const Shard& s : shards) {
        const BenchResults& r = s.results;
        const std::string there = " in " + first.file.string();
        if (!r.shards.empty()) throw shardError(s, "a merged report, not a shard (merge the shards themselves)");
        if (writtenBy(r) != writtenBy(f))
            throw shardError(s, "written by " + writtenBy(r) + ", not " + writtenBy(f) + " as" + there);
        if (const auto diff = settingsDifference(r.settings, f.settings))
            throw shardError(s, "other settings: " + *diff + there);
        if (r.shard.count != f.shard.count)
            throw shardError(s, "shard " + shardText(r.shard) + " of a run in " + std::to_string(r.shard.count) +
                                    (r.shard.count == 1 ? " shard" : " shards") + ", not " +
                                    std::to_string(f.shard.count) + " as" + there);
        if (r.configurationHash != f.configurationHash || r.configurationCount != f.configurationCount)
            throw shardError(s, "another configuration list (" + std::to_string(r.configurationCount) + ", hash " +
                                    r.configurationHash + ") than" + there);
        if (const auto [it, added] = seen.try_emplace(r.shard.index, &s); !added)
            throw shardError(s, "shard " + shardText(r.shard) + " given twice (also " + it->second->file.string() + ")");
    }
    std::string missing;
    for (int i = 0; i < f.shard.count; ++i)
        if (!seen.contains(i)) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
    if (!missing.empty())
        missing = "missing shard" + std::string(missing.find(',') == std::string::npos ? " " : "s ") + missing +
                  " of " + std::to_string(f.shard.count);
    // A shard that stopped early (bench_resume.h) is named with what it lacks, so that it can be
    // rerun alone with --resume; merging it would drop its scenes silently.
    for (const auto& [index, s] : seen) {
        const BenchResults& r = s->results;
        if (r.complete()) continue;
        std::string scenes;
        for (const std::string& file : missingScenes(r)) scenes += (scenes.empty() ? "" : ", ") + file;
        missing += std::string(missing.empty() ? "" : "; ") + "shard " + shardText(r.shard) + " (" + s->file.string() +
                   ") is incomplete: " + r.failure + (scenes.empty() ? "" : "; not measured: " + scenes) +
                   "; rerun it with --resume";
    }
    if (!missing.empty()) throw Error(missing);
}

const SceneResult* sceneOf(const BenchResults& r, int index) {
    for (const SceneResult& s : r.scenes)
        if (s.index == index) return &s;
    return nullptr;
}

// One scene of the merged report, filled configuration by configuration from the shards.
class SceneMerger {
public:
    SceneMerger(const std::vector<const Shard*>& byIndex, int scene, std::string file)
        : byIndex_(byIndex), scene_(scene), file_(std::move(file)) {}

    void add(const Configuration& c, int shard) {
        const Shard& from = *byIndex_[size_t(shard)];
        const SceneResult* s = sceneOf(from.results, scene_);
        const bool has = s && std::any_of(s->configurations.begin(), s->configurations.end(),
                                          [&](const ConfigurationRun& run) { return run.label == c.label; });
        if (!has) throw shardError(from, "has no figures for '" + c.label + "' of " + file_ + " (scene " + std::to_string(scene_ + 1) + ")");
        checkSameScene(from, *s);
        switch (c.kind) {
            case Configuration::Kind::Reference: takeReference(*s); break;
            case Configuration::Kind::Accel: takeAccel(from, *s, c.accel); break;
            case Configuration::Kind::Concurrent: merged_.concurrent = s->concurrent; break;
            case Configuration::Kind::Delta: takeDelta(from, *s, c.delta); break;
            case Configuration::Kind::MaxDepthSweep: takePoints(*s, "maxdepth", 0, depthPoints_); break;
        }
        merged_.configurations.push_back({c.label, shard});
    }

    SceneResult finish() {
        for (auto* bucket : {&deltaPoints_, &depthPoints_, &cpuPoints_})
            merged_.errorPoints.insert(merged_.errorPoints.end(), bucket->begin(), bucket->end());
        markParetoFront(merged_.errorPoints);
        if (!singles_.empty()) {
            merged_.embree.singleSamples = singles_;
            merged_.embree.packetSamples = packets_;
            merged_.embree.singleMs = spreadOf(singles_);
            merged_.embree.packetMs = spreadOf(packets_);
        }
        return std::move(merged_);
    }

private:
    // Every shard loaded the same scene at the same size.
    void checkSameScene(const Shard& from, const SceneResult& s) {
        if (!first_) {
            first_ = &s;
            merged_.index = s.index;
            merged_.file = s.file;
            merged_.name = s.name;
            merged_.view = s.view;
            merged_.triangles = s.triangles;
            merged_.width = s.width;
            merged_.height = s.height;
            merged_.maxDepth = s.maxDepth;
            return;
        }
        if (s.triangles != first_->triangles || s.width != first_->width || s.height != first_->height ||
            s.maxDepth != first_->maxDepth)
            throw shardError(from, "scene " + s.file + " has " + std::to_string(s.triangles) + " triangles at " +
                                       std::to_string(s.width) + "x" + std::to_string(s.height) + ", maxdepth " +
                                       std::to_string(s.maxDepth) + "; another shard loaded it with " +
                                       std::to_string(first_->triangles) + " triangles at " +
                                       std::to_string(first_->width) + "x" + std::to_string(first_->height) +
                                       ", maxdepth " + std::to_string(first_->maxDepth));
    }

    void takeReference(const SceneResult& s) {
        merged_.referenceAccel = s.referenceAccel;
        merged_.referenceBuildMs = s.referenceBuildMs;
        merged_.referenceRenderMs = s.referenceRenderMs;
        merged_.reference = s.reference;
        if (merged_.embree.version.empty()) merged_.embree.note = s.embree.note;
        takePoints(s, "cpu-reference", 0, cpuPoints_);
    }

    void takeAccel(const Shard& from, const SceneResult& s, const std::string& name) {
        const auto a = std::find_if(s.accels.begin(), s.accels.end(), [&](const AccelResult& x) { return x.accel == name; });
        if (a == s.accels.end()) throw shardError(from, "lists 'accel " + name + "' but has no figures for it");
        merged_.accels.push_back(*a);
        for (const ErrorPoint& p : s.errorPoints)
            if (p.group == "accelerator" && p.label == name) merged_.errorPoints.push_back(p);
        if (!s.embree.version.empty()) {
            merged_.embree.version = s.embree.version;
            merged_.embree.note.clear();
            merged_.embree.threads = s.embree.threads;
            merged_.embree.agreement = s.embree.agreement;
            // A shard's samples hold the runs of all its accelerators of the scene: taken once.
            if (pooled_.insert(&from).second) {
                singles_.insert(singles_.end(), s.embree.singleSamples.begin(), s.embree.singleSamples.end());
                packets_.insert(packets_.end(), s.embree.packetSamples.begin(), s.embree.packetSamples.end());
            }
        } else if (merged_.embree.version.empty() && merged_.embree.note.empty()) {
            merged_.embree.note = s.embree.note;
        }
    }

    void takeDelta(const Shard& from, const SceneResult& s, int delta) {
        const auto d = std::find_if(s.deltas.begin(), s.deltas.end(), [&](const DeltaResult& x) { return x.delta == delta; });
        if (d == s.deltas.end()) throw shardError(from, "lists 'aac-delta " + std::to_string(delta) + "' but has no figures for it");
        merged_.deltas.push_back(*d);
        takePoints(s, "aac-delta", delta, deltaPoints_);
    }

    static void takePoints(const SceneResult& s, const std::string& group, int delta, std::vector<ErrorPoint>& into) {
        for (const ErrorPoint& p : s.errorPoints)
            if (p.group == group && (delta == 0 || p.delta == delta)) into.push_back(p);
    }

    const std::vector<const Shard*>& byIndex_;
    int scene_;
    std::string file_;
    const SceneResult* first_ = nullptr;
    SceneResult merged_;
    // The error points in the order of an unsharded run: accelerators (added as they come), the
    // delta sweep, the maxdepth sweep, the CPU reference.
    std::vector<ErrorPoint> deltaPoints_, depthPoints_, cpuPoints_;
    std::vector<double> singles_, packets_;
    std::set<const Shard*> pooled_;  // the shards whose Embree samples are in singles_, packets_
};

// "A" when every shard says A, else "A; B" in shard order.
std::string common(const std::vector<const Shard*>& shards, std::string BenchResults::*field) {
    std::vector<std::string> seen;
    for (const Shard* s : shards)
        if (std::find(seen.begin(), seen.end(), s->results.*field) == seen.end()) seen.push_back(s->results.*field);
    std::string out;
    for (const std::string& v : seen) out += (out.empty() ? "" : "; ") + v;
    return out;
}

ShardInfo shardInfo(const Shard& s) {
    const BenchResults& r = s.results;
    size_t count = 0;
    for (const SceneResult& scene : r.scenes) count += scene.configurations.size();
    return {r.shard, r.node, r.device, r.driver, r.deviceType, r.vulkanApi, r.hardwareThreads,
            r.commandLine, r.startedAt, r.elapsedSeconds, count, s.file.string(), r.loadAverageStart,
            r.loadAverageEnd};
}

BenchResults mergedRun(const std::vector<const Shard*>& byIndex, const std::string& commandLine) {
    const BenchResults& f = byIndex.front()->results;
    BenchResults m;
    m.vkrayVersion = f.vkrayVersion;
    m.revision = f.revision;
    m.commandLine = commandLine;
    m.startedAt = f.startedAt;
    for (const Shard* s : byIndex) m.startedAt = std::min(m.startedAt, s->results.startedAt);
    m.device = common(byIndex, &BenchResults::device);
    m.driver = common(byIndex, &BenchResults::driver);
    m.deviceType = common(byIndex, &BenchResults::deviceType);
    m.vulkanApi = common(byIndex, &BenchResults::vulkanApi);
    m.node = common(byIndex, &BenchResults::node);
    m.hardwareThreads = f.hardwareThreads;
    m.repeat = f.repeat;
    m.threadCounts = f.threadCounts;
    m.settings = f.settings;
    m.configurationCount = f.configurationCount;
    m.configurationHash = f.configurationHash;
    for (const Shard* s : byIndex) m.shards.push_back(shardInfo(*s));
    return m;
}

}  // namespace

BenchResults mergeBenchReports(const std::vector<fs::path>& dirs, const std::string& commandLine) {
    if (dirs.empty()) throw Error("--merge: no shard folder given");
    std::vector<Shard> shards;
    for (const fs::path& dir : dirs) shards.push_back({dir / "bench.json", readBenchReport(dir)});
    checkShards(shards);
    std::vector<const Shard*> byIndex(shards.size());
    for (const Shard& s : shards) byIndex[size_t(s.results.shard.index)] = &s;

    const BenchSettings& settings = shards.front().results.settings;
    const std::vector<Configuration> list = configurationList(settings);
    if (configurationHash(list) != shards.front().results.configurationHash)
        throw shardError(shards.front(), "its configuration list (hash " + shards.front().results.configurationHash +
                                             ") is not the one this vkray makes of its settings (hash " +
                                             configurationHash(list) + ")");
    BenchResults merged = mergedRun(byIndex, commandLine);
    for (size_t scene = 0; scene < settings.scenes.size(); ++scene) {
        SceneMerger m(byIndex, int(scene), settings.scenes[scene]);
        for (size_t k = 0; k < list.size(); ++k)
            if (list[k].scene == int(scene)) m.add(list[k], shardOfConfiguration(k, int(byIndex.size())));
        merged.scenes.push_back(m.finish());
    }
    return merged;
}

}  // namespace vkray::bench
