// The tables and sentences shared by bench.md and report.html (see report_tables.h).
#include "bench/report_tables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "accel/accel.h"
#include "core/error.h"

namespace vkray::bench {
namespace {

std::string printed(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

// 69668 -> "69,668"
std::string withThousands(uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

std::string threadsText(int n) { return std::to_string(n) + (n == 1 ? " thread" : " threads"); }

std::string joinInts(const std::vector<int>& v) {
    std::string out;
    for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + std::to_string(v[i]);
    return out;
}

// "¹", "²", ..., "¹²": footnote marks that need no markup in either format.
std::string superscript(size_t n) {
    static const char* digits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
    std::string out;
    for (char c : std::to_string(n)) out += digits[c - '0'];
    return out;
}

// Footnotes of one table: the same text gets the same number.
class Footnotes {
public:
    std::string mark(const std::string& note) {
        auto [it, added] = numbers_.try_emplace(note, numbers_.size() + 1);
        if (added) texts_.push_back(superscript(it->second) + " " + note);
        return superscript(it->second);
    }
    const std::vector<std::string>& texts() const { return texts_; }

private:
    std::map<std::string, size_t> numbers_;
    std::vector<std::string> texts_;
};

const ThreadTiming* timingAt(const AccelResult& a, int threads) {
    for (const ThreadTiming& t : a.build)
        if (t.threads == threads) return &t;
    return nullptr;
}

// The build with the most threads: what "build ms" means everywhere else in the report.
const ThreadTiming* fullBuild(const AccelResult& a) {
    const auto it = std::max_element(a.build.begin(), a.build.end(),
                                     [](const ThreadTiming& x, const ThreadTiming& y) { return x.threads < y.threads; });
    return it == a.build.end() ? nullptr : &*it;
}

std::string rayKindCell(const AccelResult& a, const std::string& kind, Footnotes& notes) {
    for (const RayKindFigures& k : a.rayKinds) {
        if (k.kind != kind) continue;
        if (k.mraysPerSecond) return formatNumber(*k.mraysPerSecond);
        return k.note.empty() ? kMissing : kMissing + notes.mark(k.note);
    }
    return kMissing;
}

Table makeTable(std::string title, std::vector<std::string> columns, std::vector<bool> numeric) {
    Table t;
    t.title = std::move(title);
    t.columns = std::move(columns);
    t.numeric = std::move(numeric);
    return t;
}

void addRow(Table& t, std::vector<std::string> cells, bool marked = false) {
    t.rows.push_back(std::move(cells));
    t.marked.push_back(marked);
}

// The accelerators of one family with a usable trace time, fastest first.
std::vector<const AccelResult*> rankedFamily(const SceneResult& scene, accel::Family family) {
    std::vector<const AccelResult*> out;
    for (const AccelResult& a : scene.accels)
        if (familyOf(a.accel) == family && a.traceMs.median > 0.0 && std::isfinite(a.traceMs.median))
            out.push_back(&a);
    std::stable_sort(out.begin(), out.end(), [](const AccelResult* x, const AccelResult* y) {
        return x->traceMs.median < y->traceMs.median;
    });
    return out;
}

std::string traceFigures(const AccelResult& fast, const AccelResult& slow) {
    return "(" + formatNumber(fast.traceMs.median) + " ms against " + formatNumber(slow.traceMs.median) + " ms)";
}

// "X traces 2.40x faster than Y, the fastest kd traversal (1.2 ms against 2.9 ms)."
std::string fasterSentence(const AccelResult& fast, const AccelResult& slow, const std::string& slowRole) {
    if (fast.traceMs.median == slow.traceMs.median)
        return fast.accel + " and " + slow.accel + " (" + slowRole + ") trace equally fast (" +
               formatNumber(fast.traceMs.median) + " ms).";
    return fast.accel + " traces " + formatRatio(slow.traceMs.median / fast.traceMs.median) + " faster than " +
           slow.accel + ", " + slowRole + " " + traceFigures(fast, slow) + ".";
}

std::string familyRole(const std::vector<const AccelResult*>& family, const char* what) {
    return std::string(family.size() == 1 ? "the only " : "the fastest ") + what;
}

// Among one family: the fastest against the slowest.
std::string withinFamily(const std::vector<const AccelResult*>& family, const char* plural) {
    if (family.size() < 2) return "";
    const AccelResult& fast = *family.front();
    const AccelResult& slow = *family.back();
    return std::string("Among the ") + plural + ", " + fast.accel + " is fastest, " +
           formatRatio(slow.traceMs.median / fast.traceMs.median) + " faster than " + slow.accel +
           ", the slowest " + traceFigures(fast, slow) + ".";
}

}  // namespace

std::optional<accel::Family> familyOf(const std::string& accelName) {
    try {
        return accel::resolveAccel(accelName).family;
    } catch (const Error&) {
        return std::nullopt;  // a name this build does not know: in no family
    }
}

std::string accelAbout(const std::string& accelName) {
    if (familyOf(accelName) != accel::Family::Driver) return "";
    return "the driver's own BVH and traversal (VK_KHR_ray_query; in hardware on GPUs with ray-tracing units)";
}

std::vector<std::string> accelAboutNotes(const SceneResult& scene) {
    std::vector<std::string> out;
    for (const AccelResult& a : scene.accels) {
        std::string about = accelAbout(a.accel);
        if (about.empty()) continue;
        about = a.accel + ": " + about;
        if (a.buildOnDevice)
            about += "; its build is the driver's on the device (GPU timestamps, in each timed full render) "
                     "plus vkray's Morton ordering of the triangles on the CPU, its structure the driver's";
        out.push_back(about + ".");
    }
    return out;
}

// ---- Formatting -------------------------------------------------------------------------------

std::string formatNumber(double v) {
    if (!std::isfinite(v)) return kMissing;
    const double a = std::abs(v);
    if (a < 1.0) return printed("%.2g", v);
    if (a < 100.0) return printed("%.1f", v);
    return printed("%.0f", v);
}

std::string formatSpread(const Spread& s) {
    return formatNumber(s.median) + " (" + formatNumber(s.min) + "–" + formatNumber(s.max) + ")";
}

std::string formatRatio(double r) { return std::isfinite(r) ? printed("%.2fx", r) : kMissing; }

std::string formatBytes(uint64_t bytes) {
    const double b = double(bytes);
    if (bytes < 1024) return std::to_string(bytes) + " B";
    if (b < 1024.0 * 1024.0) return printed("%.1f KiB", b / 1024.0);
    if (b < 1024.0 * 1024.0 * 1024.0) return printed("%.2f MiB", b / (1024.0 * 1024.0));
    return printed("%.2f GiB", b / (1024.0 * 1024.0 * 1024.0));
}

std::string formatPerRay(double v) {
    if (!std::isfinite(v)) return kMissing;
    return printed(std::abs(v) < 10.0 ? "%.2f" : "%.1f", v);
}

std::string perRayCell(const AccelResult& a, double v) { return a.traversalCounted ? formatPerRay(v) : kMissing; }

std::string formatRmse(double rmse) {
    if (!std::isfinite(rmse)) return kMissing;
    return rmse == 0.0 ? "0" : printed("%.3g", rmse);
}

std::string formatPsnr(const std::optional<double>& psnr) { return psnr ? printed("%.1f", *psnr) : "identical"; }

std::string formatPercent(double fraction) {
    return std::isfinite(fraction) ? printed("%.2f %%", 100.0 * fraction) : kMissing;
}

std::string formatChange(double fraction) {
    if (!std::isfinite(fraction)) return kMissing;
    const double percent = 100.0 * fraction;
    std::string s = printed(std::abs(percent) < 9.95 ? "%.1f" : "%.0f", std::abs(percent));
    if (s == "0.0") return "0 %";
    return (percent < 0.0 ? "−" : "+") + s + " %";  // a true minus sign, as wide as the plus
}

std::string concurrentAgainstSum(double concurrentMs, double sumMs) {
    if (!std::isfinite(concurrentMs) || !std::isfinite(sumMs)) return kMissing;
    const double change = concurrentMs - sumMs;
    const std::string sum = "the " + formatNumber(sumMs) + " ms sum";
    const std::string share = sumMs > 0.0 ? " (" + formatChange(change / sumMs) + ")" : "";
    if (change == 0.0) return "as fast as " + sum + share;
    return formatNumber(std::abs(change)) + " ms " + (change < 0.0 ? "faster" : "slower") + " than " + sum + share;
}

// ---- Facts ------------------------------------------------------------------------------------

Facts runFacts(const BenchResults& r) {
    std::string kind = r.deviceType;
    if (!r.vulkanApi.empty()) kind += (kind.empty() ? "" : ", ") + std::string("Vulkan ") + r.vulkanApi;
    std::string version = r.vkrayVersion;
    if (!r.revision.empty()) version += " (revision " + r.revision + ")";
    std::string started = r.startedAt;
    if (r.elapsedSeconds > 0.0) started += ", took " + formatNumber(r.elapsedSeconds) + " s";
    std::string threads = std::to_string(r.hardwareThreads);
    if (!r.threadCounts.empty()) threads += "; build scaling at " + joinInts(r.threadCounts) + " threads";

    return {{"Device", r.device},
            {"Device type", kind},
            {"Driver", r.driver},
            {"vkray", version},
            {"Command", r.commandLine},
            {"Started (UTC)", started},
            {"Repeats", std::to_string(r.repeat) + " timed runs after one warm-up; medians with the min–max spread"},
            {"Hardware threads", threads}};
}

Facts sceneFacts(const SceneResult& s) {
    return {{"Scene file", s.file},
            {"Triangles", withThousands(s.triangles)},
            {"Image", std::to_string(s.width) + "x" + std::to_string(s.height) + ", maxdepth " +
                          std::to_string(s.maxDepth)},
            {"Camera", s.view == "scene"   ? std::string("the scene's")
                       : s.view == "close" ? std::string("close-up (--view close)")
                                           : "--view " + s.view},
            {"Reference", "CPU renderer in double precision with the " + s.referenceAccel + " traversal: built in " +
                              formatNumber(s.referenceBuildMs) + " ms, rendered in " +
                              formatNumber(s.referenceRenderMs) + " ms"}};
}

// ---- Tables -----------------------------------------------------------------------------------

Table acceleratorTable(const SceneResult& scene) {
    Table t = makeTable("Accelerators",
                        {"accel", "build ms", "structure", "trace ms", "Mrays/s", "primary Mrays/s", "shadow Mrays/s",
                         "secondary Mrays/s", "nodes/ray", "leaves/ray", "triangles/ray", "restarts/ray", "capped rays",
                         "RMSE", "PSNR dB", "primary mismatch"},
                        {false, true, true, true, true, true, true, true, true, true, true, true, true, true, true, true});
    Footnotes notes;
    for (const AccelResult& a : scene.accels) {
        const ThreadTiming* build = fullBuild(a);
        addRow(t, {a.accel, build ? formatSpread(build->ms) : kMissing, formatBytes(a.structureBytes),
                   formatSpread(a.traceMs), formatNumber(a.mraysPerSecond), rayKindCell(a, "primary", notes),
                   rayKindCell(a, "shadow", notes), rayKindCell(a, "secondary", notes), perRayCell(a, a.nodesPerRay),
                   perRayCell(a, a.leavesPerRay), perRayCell(a, a.trianglesPerRay), perRayCell(a, a.restartsPerRay),
                   std::to_string(a.cappedRays), formatRmse(a.error.rmse), formatPsnr(a.error.psnr),
                   formatPercent(a.error.primaryMismatch)});
    }
    t.notes.push_back("Build: CPU, with the most threads measured; trace: the full render on the GPU (timestamps). "
                      "Times in ms, medians with the min–max spread. Per-ray counts over rays of all kinds, from the "
                      "statistics variant of each kernel. Error against the reference; primary mismatch: pixels "
                      "whose primary hit differs.");
    for (const std::string& n : accelAboutNotes(scene)) t.notes.push_back(n);
    for (const std::string& n : notes.texts()) t.notes.push_back(n);
    t.whenEmpty = "No accelerator was run on this scene.";
    return t;
}

std::vector<int> buildThreadCounts(const SceneResult& scene) {
    std::set<int> counts;
    for (const AccelResult& a : scene.accels)
        if (!a.buildOnDevice)
            for (const ThreadTiming& t : a.build) counts.insert(t.threads);
    return {counts.begin(), counts.end()};
}

std::optional<double> buildSpeedup(const AccelResult& a, int baseThreads, int threads) {
    const ThreadTiming* base = timingAt(a, baseThreads);
    const ThreadTiming* at = timingAt(a, threads);
    if (!base || !at || !(base->ms.median > 0.0) || !(at->ms.median > 0.0)) return std::nullopt;
    return base->ms.median / at->ms.median;
}

Table buildScalingTable(const SceneResult& scene) {
    const std::vector<int> counts = buildThreadCounts(scene);
    const int base = counts.empty() ? 1 : counts.front();  // 1 when measured: the set is ascending
    Table t = makeTable("Build scaling", {"accel"}, {false});
    for (int n : counts) {
        t.columns.push_back("ms, " + threadsText(n));
        t.numeric.push_back(true);
        if (n == base) continue;
        t.columns.push_back("speed-up, " + threadsText(n));
        t.numeric.push_back(true);
    }
    for (const AccelResult& a : scene.accels) {
        if (a.build.empty() || a.buildOnDevice) continue;  // the driver's build on the device: no CPU threads
        std::vector<std::string> row{a.accel};
        for (int n : counts) {
            const ThreadTiming* at = timingAt(a, n);
            row.push_back(at ? formatNumber(at->ms.median) : kMissing);
            if (n == base) continue;
            const std::optional<double> s = buildSpeedup(a, base, n);
            row.push_back(s ? formatRatio(*s) : kMissing);
        }
        addRow(t, row);
    }
    t.notes.push_back("CPU build time, medians in ms; speed-up = time with " + threadsText(base) +
                      " / time with n threads (as in Table 5.7 of A. F. Mahmuda, \"Bounding Volume Hierarchy "
                      "Construction Using Agglomerative Clustering for Faster Ray Tracing\", 2017).");
    t.whenEmpty = "No build timings were measured for this scene.";
    return t;
}

Table concurrentBuildTable(const SceneResult& scene) {
    Table t = makeTable("Concurrent build", {"build", "ms"}, {false, true});
    t.whenEmpty = "No concurrent build was measured for this scene (it needs a BVH and a kd-tree).";
    if (!scene.concurrent) return t;
    const ConcurrentBuild& c = *scene.concurrent;
    const Spread sum{c.bvhMs.median + c.kdMs.median, c.bvhMs.min + c.kdMs.min, c.bvhMs.max + c.kdMs.max};
    addRow(t, {c.bvhAccel + " alone", formatSpread(c.bvhMs)});
    addRow(t, {c.kdAccel + " alone", formatSpread(c.kdMs)});
    addRow(t, {"one after the other (sum)", formatSpread(sum)});
    addRow(t, {"both at once (wall clock)", formatSpread(c.concurrentMs)});
    addRow(t, {"both at once against the sum", concurrentAgainstSum(c.concurrentMs.median, sum.median)},
           c.concurrentMs.median < sum.median);
    t.notes.push_back("Each build with all threads; the sum adds the medians (and the minima, the maxima) of the "
                      "separate builds. The last row compares the medians: the change in ms and as a share of the "
                      "sum, negative when building both at once is faster.");
    return t;
}

std::optional<size_t> bestDelta(const SceneResult& scene) {
    std::optional<size_t> best;
    for (size_t i = 0; i < scene.deltas.size(); ++i) {
        const DeltaResult& d = scene.deltas[i];
        const double total = d.buildMs.median + d.traceMs.median;
        if (!best || total < scene.deltas[*best].buildMs.median + scene.deltas[*best].traceMs.median) best = i;
    }
    return best;
}

Table deltaSweepTable(const SceneResult& scene) {
    Table t = makeTable("AAC delta sweep",
                        {"delta", "epsilon", "build ms", "trace ms", "total ms", "nodes/ray", "triangles/ray",
                         "tests/ray", "SAH cost (BVH)"},
                        std::vector<bool>(9, true));
    const std::optional<size_t> best = bestDelta(scene);
    for (size_t i = 0; i < scene.deltas.size(); ++i) {
        const DeltaResult& d = scene.deltas[i];
        const bool isBest = best == i;
        addRow(t,
               {std::to_string(d.delta) + (isBest ? std::string(" ") + kStar : ""), printed("%g", d.epsilon),
                formatNumber(d.buildMs.median), formatNumber(d.traceMs.median),
                formatNumber(d.buildMs.median + d.traceMs.median), formatPerRay(d.nodesPerRay),
                formatPerRay(d.trianglesPerRay), formatPerRay(d.nodesPerRay + d.trianglesPerRay),
                printed("%.4g", d.sahCost)},  // presets differ by a few percent: show them
               isBest);
    }
    t.notes.push_back(std::string(kStar) + " the lowest build + trace total. Medians in ms (build: all threads). "
                      "Tests per ray = nodes + triangles per ray, the intersection tests of Tables 5.5 and 5.6 of "
                      "A. F. Mahmuda, \"Bounding Volume Hierarchy Construction Using Agglomerative "
                      "Clustering for Faster Ray Tracing\", 2017.");
    t.notes.push_back("SAH cost: the BVH's, relative to the root's surface area, in units of Ct=1 a node and Ci=1 "
                      "a triangle (sah_cost of vkray render --stats); a kd-tree's sah_cost weighs a triangle 20 "
                      "times as much and does not compare with it.");
    t.whenEmpty = "No AAC delta sweep was run for this scene.";
    return t;
}

Table errorTable(const SceneResult& scene) {
    Table t = makeTable("Error against run time",
                        {"group", "configuration", "precision", "maxdepth", "build ms", "trace ms", "total ms", "RMSE",
                         "PSNR dB", "primary mismatch", "Pareto"},
                        {false, false, false, true, true, true, true, true, true, true, false});
    for (const ErrorPoint& p : scene.errorPoints)
        addRow(t,
               {p.group, p.label, p.precision, p.maxDepth > 0 ? std::to_string(p.maxDepth) : kMissing, formatNumber(p.buildMs),
                formatNumber(p.traceMs), formatNumber(p.totalMs()), formatRmse(p.error.rmse),
                formatPsnr(p.error.psnr), formatPercent(p.error.primaryMismatch), p.pareto ? kStar : ""},
               p.pareto);
    t.notes.push_back(std::string(kStar) + " on the Pareto front: no other configuration is at least as fast and at "
                      "least as accurate, and better in one. Medians in ms; error against the reference.");
    t.whenEmpty = "No error measurements for this scene.";
    return t;
}

// Primary rays against the CPU yardstick: Embree's own rows, then every accelerator's camera-ray rate
// with its ratio to Embree rtcIntersect1 (the scene's one figure, so the ratios order the rows as the
// rates do), to bvh's and, when the run measured it, to rayquery's (the driver's own traversal).
Table embreeTable(const SceneResult& scene) {
    const bool rayQuery = yardstick(scene, "rayquery") != nullptr;
    Table t = makeTable("Primary rays against Embree",
                        {"tracer", "camera rays ms", "Mrays/s", "vs Embree rtcIntersect1", "vs bvh", "node steps a ray",
                         "SIMD efficiency"},
                        {false, true, true, true, true, true, true});
    if (rayQuery) {
        t.columns.insert(t.columns.begin() + 5, "x rayquery");
        t.numeric.insert(t.numeric.begin() + 5, true);
    }
    const EmbreeResult& e = scene.embree;
    if (e.version.empty()) {
        t.whenEmpty = "No CPU baseline: " + e.note + ".";
        return t;
    }
    const double rays = double(scene.width) * double(scene.height);
    const auto cell = [](std::optional<double> v, std::string (*format)(double)) {
        return v ? format(*v) : std::string(kMissing);
    };
    const auto embreeRow = [&](const std::string& tracer, const Spread& ms, const std::string& vsEmbree) {
        std::vector<std::string> row{tracer, formatSpread(ms), cell(mraysPerSecond(rays, ms.median), formatNumber),
                                     vsEmbree, kMissing, kMissing, kMissing};
        if (rayQuery) row.push_back(kMissing);
        addRow(t, row);
    };
    embreeRow(e.version + " rtcIntersect1", e.singleMs, "1.00x");
    embreeRow(e.version + " rtcIntersect16", e.packetMs, formatRatio(e.singleMs.median / e.packetMs.median));
    for (const AccelResult& a : scene.accels) {
        const std::optional<double> simd = a.primarySimdEfficiency();
        std::vector<std::string> row{a.accel, formatSpread(a.primaryOnlyMs), cell(a.primaryMrays(), formatNumber),
                                     cell(primaryVsEmbree(scene, a), formatRatio),
                                     cell(primaryVs(scene, a, "bvh"), formatRatio), perRayCell(a, a.primaryNodesPerRay),
                                     simd ? formatPercent(*simd) + ", " + std::to_string(a.simdLanes) + " lanes"
                                          : std::string(kMissing)};
        if (rayQuery) row.insert(row.begin() + 5, cell(primaryVs(scene, a, "rayquery"), formatRatio));
        addRow(t, row);
    }
    t.notes.push_back("Camera rays only (no lights, maxdepth 1): GPU time from timestamps, Embree wall-clock on " +
                      std::to_string(e.threads) + " threads, the same rays, medians with the min–max spread. "
                      "Embree runs interleaved with every accelerator's repeats; its rows summarise all of those "
                      "runs, and every ratio divides by that one median, so a higher rate always has a higher "
                      "ratio. vs bvh: the camera-ray rate over bvh's" +
                      std::string(rayQuery ? "; x rayquery: over rayquery's (rayquery's camera-ray time over the "
                                             "accelerator's)"
                                           : "") +
                      ". Embree names the reference's primary triangle on " + formatPercent(e.agreement) +
                      " of the camera rays. Node steps and SIMD efficiency from the statistics variant: the steps a "
                      "ray over the steps a ray as the device's subgroups (of the lanes given) run them, each until "
                      "its slowest lane is done (Aila and Laine 2009); for bvh-packet and kd-packet, the steps their "
                      "packets took: the SIMD efficiency is then the lanes' use of them, the share of the steps in "
                      "which a lane's ray entered the node.");
    for (const std::string& n : accelAboutNotes(scene)) t.notes.push_back(n);
    return t;
}

std::vector<Table> sceneTables(const SceneResult& scene) {
    return {acceleratorTable(scene), embreeTable(scene), buildScalingTable(scene), concurrentBuildTable(scene), deltaSweepTable(scene),
            errorTable(scene)};
}

// ---- Who wins ---------------------------------------------------------------------------------

std::string whoWins(const SceneResult& scene) {
    const auto bvh = rankedFamily(scene, accel::Family::Bvh);
    const auto kd = rankedFamily(scene, accel::Family::Kd);
    if (bvh.empty() && kd.empty()) return "No BVH or kd-tree accelerator has a trace time to compare.";

    std::string out;
    if (!bvh.empty() && !kd.empty()) {
        const bool bvhWins = bvh.front()->traceMs.median <= kd.front()->traceMs.median;
        out = bvhWins ? fasterSentence(*bvh.front(), *kd.front(), familyRole(kd, "kd traversal"))
                      : fasterSentence(*kd.front(), *bvh.front(), familyRole(bvh, "BVH"));
    } else if (bvh.empty()) {
        out = "No BVH was run.";
        if (kd.size() == 1) out += " " + kd.front()->accel + " traces in " + formatNumber(kd.front()->traceMs.median) + " ms.";
    } else {
        out = "No kd-tree traversal was run.";
        if (bvh.size() == 1)
            out += " " + bvh.front()->accel + " traces in " + formatNumber(bvh.front()->traceMs.median) + " ms.";
    }
    if (const std::string s = withinFamily(kd, "kd traversals"); !s.empty()) out += " " + s;
    if (kd.empty())
        if (const std::string s = withinFamily(bvh, "BVHs"); !s.empty()) out += " " + s;
    return out;
}

}  // namespace vkray::bench
