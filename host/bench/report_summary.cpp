// What the report says about the run as a whole (report.h, report_tables.h): its warnings, the
// console summary, and the comparison of camera rays across scenes.
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_shard.h"
#include "bench/report.h"
#include "bench/report_tables.h"

namespace vkray::bench {
namespace {

// Fewer runs than this give a min–max spread that says nothing about the noise.
constexpr int kFewestRepeats = 3;

std::string load(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

// A 1-minute load average above the cores means other work competed with the measurements (the
// run itself keeps at most all cores busy).
std::optional<std::string> loadWarning(std::optional<double> start, std::optional<double> end, int cores,
                                       const std::string& who) {
    const bool busy = (start && *start > cores) || (end && *end > cores);
    if (!busy || cores <= 0) return std::nullopt;
    std::string when;
    if (start) when = load(*start) + " at the start";
    if (end) when += (when.empty() ? "" : " and ") + load(*end) + " at the end";
    return who + "the machine was busy: its 1-minute load average was " + when + " of the run, above its " +
           std::to_string(cores) + (cores == 1 ? " core" : " cores") +
           "; other work competed with the measurements, so times are slower and spreads wider than on an idle "
           "machine";
}

// printf into a std::string.
std::string printed(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string printed(const char* format, ...) {
    char buf[512];
    va_list args;
    va_start(args, format);
    std::vsnprintf(buf, sizeof buf, format, args);
    va_end(args);
    return buf;
}

std::string accelLine(const SceneResult& s, const AccelResult& a) {
    const double buildMs = a.build.empty() ? 0.0 : a.build.back().ms.median;
    const std::string nodes = a.traversalCounted ? printed("%6.1f", a.nodesPerRay) : "     —";
    std::string out = printed("  %-14s build %9.1f ms  trace %9.1f ms  %7.2f Mrays/s  %s nodes/ray  RMSE %.4f",
                              a.accel.c_str(), buildMs, a.traceMs.median, a.mraysPerSecond, nodes.c_str(), a.error.rmse);
    if (const auto camera = a.primaryMrays()) out += printed("  camera rays %7.2f Mrays/s", *camera);
    std::vector<std::string> ratios;
    if (const auto overEmbree = primaryVsEmbree(s, a)) ratios.push_back(printed("%.3fx Embree", *overEmbree));
    for (const char* name : {"bvh", "rayquery"})
        if (const auto over = a.accel != name ? primaryVs(s, a, name) : std::nullopt)
            ratios.push_back(printed("%.2fx %s", *over, name));
    std::string joined;
    for (const std::string& r : ratios) joined += (joined.empty() ? "" : ", ") + r;
    if (!joined.empty()) out += " (" + joined + ")";
    return out + "\n";
}

// What every ratio of the summary is taken against.
enum class Yardstick { Embree, Bvh, None };

// Embree when every scene with accelerators has its figure, else bvh when every one ran it.
Yardstick yardstickOf(const BenchResults& r) {
    bool embree = true, bvh = true;
    for (const SceneResult& s : r.scenes) {
        if (s.accels.empty()) continue;
        embree = embree && s.embree.measured();
        bvh = bvh && yardstick(s, "bvh") != nullptr;
    }
    return embree ? Yardstick::Embree : bvh ? Yardstick::Bvh : Yardstick::None;
}

std::vector<const SceneResult*> scenesWithAccels(const BenchResults& r) {
    std::vector<const SceneResult*> out;
    for (const SceneResult& s : r.scenes)
        if (!s.accels.empty()) out.push_back(&s);
    return out;
}

// Column titles: the scene names, a repeated one numbered ("bunny", "bunny (2)").
std::vector<std::string> sceneColumns(const std::vector<const SceneResult*>& scenes) {
    std::map<std::string, int> seen;
    std::vector<std::string> out;
    for (const SceneResult* s : scenes) {
        const int n = ++seen[s->name];
        out.push_back(n == 1 ? s->name : s->name + " (" + std::to_string(n) + ")");
    }
    return out;
}

}  // namespace

std::vector<std::string> runWarnings(const BenchResults& r) {
    std::vector<std::string> out;
    if (r.repeat > 0 && r.repeat < kFewestRepeats)
        out.push_back("--repeat " + std::to_string(r.repeat) + ": spreads of fewer than " +
                      std::to_string(kFewestRepeats) + " runs are noise; compare figures of --repeat " +
                      std::to_string(kFewestRepeats) + " or more");
    if (r.shards.empty()) {
        if (auto w = loadWarning(r.loadAverageStart, r.loadAverageEnd, r.hardwareThreads, "")) out.push_back(*w);
    }
    for (const ShardInfo& s : r.shards)
        if (auto w = loadWarning(s.loadAverageStart, s.loadAverageEnd, s.hardwareThreads,
                                 "shard " + shardText(s.shard) + " on " + s.node + ": "))
            out.push_back(*w);
    return out;
}

std::string benchSummary(const BenchResults& r) {
    std::string out = "device: " + r.device + " (" + r.driver + ")\n";
    size_t measured = 0;
    for (const SceneResult& s : r.scenes) measured += s.configurations.size();
    if (r.shard.count > 1)
        out += printed("shard %s on %s: %zu of %zu configurations\n", shardText(r.shard).c_str(), r.node.c_str(),
                       measured, r.configurationCount);
    if (!r.shards.empty())
        out += printed("merged %zu shards: %zu of %zu configurations\n", r.shards.size(), measured, r.configurationCount);
    for (const SceneResult& s : r.scenes) {
        out += printed("%s (%llu triangles, %dx%d):\n", s.file.c_str(), (unsigned long long)s.triangles, s.width,
                       s.height);
        const double pixels = double(s.width) * double(s.height);
        if (const auto single = mraysPerSecond(pixels, s.embree.singleMs.median); !s.embree.version.empty() && single)
            out += printed("  %-14s camera rays %7.2f Mrays/s (rtcIntersect1), %7.2f Mrays/s (rtcIntersect16)\n",
                           "Embree", *single, mraysPerSecond(pixels, s.embree.packetMs.median).value_or(0.0));
        else if (!s.embree.note.empty())
            out += printed("  %-14s %s\n", "Embree", s.embree.note.c_str());
        for (const AccelResult& a : s.accels) out += accelLine(s, a);
        for (const std::string& about : accelAboutNotes(s)) out += "  " + about + "\n";
    }
    return out;
}

std::optional<Table> summaryTable(const BenchResults& r) {
    const std::vector<const SceneResult*> scenes = scenesWithAccels(r);
    if (scenes.size() < 2) return std::nullopt;  // one scene's table says it all
    Table t;
    const Yardstick yardstick = yardstickOf(r);
    const bool embree = yardstick == Yardstick::Embree;
    t.title = std::string("Camera rays across scenes") +
              (yardstick == Yardstick::None ? "" : embree ? ": rate over Embree rtcIntersect1's" : ": rate over bvh's");
    if (yardstick == Yardstick::None) {
        t.whenEmpty = "No yardstick common to every scene: neither Embree nor bvh ran on all of them.";
        return t;
    }
    t.columns = {"accel"};
    for (const std::string& c : sceneColumns(scenes)) t.columns.push_back(c);
    t.columns.push_back("geometric mean");
    t.numeric.assign(t.columns.size(), true);
    t.numeric[0] = false;

    std::vector<std::string> names;  // every accelerator, in order of first appearance
    for (const SceneResult* s : scenes)
        for (const AccelResult& a : s->accels)
            if (std::find(names.begin(), names.end(), a.accel) == names.end()) names.push_back(a.accel);
    std::vector<double> means(names.size(), 0.0);
    std::map<size_t, std::string> partial;  // row: "over 2 of 3 scenes"
    for (size_t i = 0; i < names.size(); ++i) {
        std::vector<std::string> row{names[i]};
        double logSum = 0.0;
        size_t n = 0;
        for (const SceneResult* s : scenes) {
            std::optional<double> ratio;
            for (const AccelResult& a : s->accels)
                if (a.accel == names[i]) ratio = embree ? primaryVsEmbree(*s, a) : primaryVs(*s, a, "bvh");
            row.push_back(ratio ? formatRatio(*ratio) : kMissing);
            if (ratio && *ratio > 0.0) logSum += std::log(*ratio), ++n;
        }
        means[i] = n > 0 ? std::exp(logSum / double(n)) : 0.0;
        if (n > 0 && n < scenes.size())
            partial[i] = "over " + std::to_string(n) + " of " + std::to_string(scenes.size()) + " scenes";
        row.push_back(n > 0 ? formatRatio(means[i]) : kMissing);
        t.rows.push_back(std::move(row));
    }
    // The best mean among the accelerators with a ratio in every scene: a mean over fewer scenes
    // does not compare with theirs.
    double best = 0.0;
    for (size_t i = 0; i < names.size(); ++i)
        if (!partial.contains(i)) best = std::max(best, means[i]);
    for (size_t i = 0; i < names.size(); ++i) {
        const bool marked = best > 0.0 && !partial.contains(i) && means[i] == best;
        if (marked) t.rows[i].back() += std::string(" ") + kStar;
        if (partial.contains(i)) t.rows[i].back() += " (" + partial[i] + ")";
        t.marked.push_back(marked);
    }
    t.notes.push_back(std::string(embree ? "Each scene's camera-ray rate over Embree rtcIntersect1's on the same rays "
                                           "(the scene's one Embree figure, as in its table \"Primary rays against "
                                           "Embree\")"
                                         : "Each scene's camera-ray rate over bvh's (no Embree figure in every scene)") +
                      "; the geometric mean over the scenes weighs every scene alike, whatever its size. " + kStar +
                      " the highest mean of the accelerators run on every scene.");
    t.whenEmpty = "No accelerator was run.";
    return t;
}

}  // namespace vkray::bench
