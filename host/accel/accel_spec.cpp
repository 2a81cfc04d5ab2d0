#include "accel/accel_spec.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>

#include "core/error.h"
#include "core/format.h"
#include "core/suggest.h"
#include "scene/text_input.h"

namespace vkray::accel {
namespace {

// ---- The accelerators ---------------------------------------------------------------------------

struct AccelEntry {
    std::string_view name;
    Family family;
    bvh::Config bvh;  // Family::Bvh: the preset
    kd::Traversal kdTraversal = kd::Traversal::Restart;
    BvhWalk bvhWalk = BvhWalk::Stack;
};

// Plain `bvh` is AAC-HQ with two passes of treelet restructuring (Karras and Aila 2013): camera
// rays take fewer node steps than in AAC-HQ's tree for a longer build, and a render traces far more
// rays than the build touches primitives (docs/bvh.md, "Default preset", has the figures).
// bvh-fast and bvh-hq are the two presets of Gu, He, Fatahalian and Blelloch, "Efficient BVH
// Construction via Approximate Agglomerative Clustering", HPG 2013, as published.
const AccelEntry kAccels[] = {
    {"bvh", Family::Bvh, bvh::Config::aacHqRestructured()},
    {"bvh-fast", Family::Bvh, bvh::Config::aacFast()},
    {"bvh-hq", Family::Bvh, bvh::Config::aacHq()},
    {"bvh-sah", Family::Bvh, bvh::Config::binnedSah()},
    // bvh's tree walked without a stack (Hapala et al. 2011; docs/bvh.md).
    {"bvh-stackless", Family::Bvh, bvh::Config::aacHqRestructured(), {}, BvhWalk::Stackless},
    // bvh's tree walked by the rays of a subgroup as one packet (Günther, Popov, Seidel and
    // Slusallek 2007; docs/bvh.md).
    {"bvh-packet", Family::Bvh, bvh::Config::aacHqRestructured(), {}, BvhWalk::Packet},
    // AAC-HQ with sphere containers instead of boxes: Mahmuda 2017's box/sphere experiment
    // (docs/bvh.md, "Sphere containers").
    {"bvh-sphere", Family::Bvh, bvh::Config::aacHqSpheres()},
    {"kd-restart", Family::Kd, {}, kd::Traversal::Restart},
    {"kd-pushdown", Family::Kd, {}, kd::Traversal::PushDown},
    {"kd-ropes", Family::Kd, {}, kd::Traversal::Ropes},
    {"kd-backtrack", Family::Kd, {}, kd::Traversal::Backtrack},
    {"kd-stack", Family::Kd, {}, kd::Traversal::Stack},
    {"kd-shortstack", Family::Kd, {}, kd::Traversal::ShortStack},
    // kd-stack's tree walked by the rays of a subgroup as packets (Wald et al. 2001; Horn et al.
    // 2007; docs/kdtree.md).
    {"kd-packet", Family::Kd, {}, kd::Traversal::Packet},
    {"brute", Family::Brute, {}},
    // The driver's own BVH and traversal (VK_KHR_acceleration_structure, VK_KHR_ray_query): in
    // hardware on GPUs with ray-tracing units. A yardstick beside Embree, not one of vkray's own.
    {"rayquery", Family::Driver, {}},
};

// ---- The tuning options -------------------------------------------------------------------------

bool isAac(const AccelSpec& s) {
    return s.family == Family::Bvh && s.bvh.builder == bvh::Config::Builder::Aac;
}
bool isKd(const AccelSpec& s) { return s.family == Family::Kd; }
bool isKdShortStack(const AccelSpec& s) { return isKd(s) && s.kdTraversal == kd::Traversal::ShortStack; }
bool isBvh(const AccelSpec& s) { return s.family == Family::Bvh; }
bool isDriver(const AccelSpec& s) { return s.family == Family::Driver; }
// Treelet restructuring prices boxes: not for sphere containers.
bool isBoxBvh(const AccelSpec& s) { return isBvh(s) && s.bvh.container == bvh::Config::Container::Box; }

// A leaf range is clustered by an all-pairs search, O(delta^2) per merge: the bound keeps a typo from
// turning a build into hours. The kd costs' bound keeps their products finite.
const TuningOption kTuning[] = {
    {"aac-delta", "AAC: leaf-range size delta", isAac, 1, bvh::Config::kMaxDelta, false, true, "",
     [](AccelSpec& s, double v) { s.bvh.delta = int(v); }},
    {"aac-epsilon", "AAC: reduction exponent, alpha = 1/2 - epsilon", isAac, 0.0, 0.5, true, false,
     "aac-epsilon must be in [0, 0.5) (alpha = 1/2 - epsilon must stay positive)",
     [](AccelSpec& s, double v) { s.bvh.epsilon = v; }},
    {"bvh-treelet-passes", "BVH: treelet restructuring passes after the build (bvh: 2)", isBoxBvh, 0, 16, false,
     true, "", [](AccelSpec& s, double v) { s.bvh.treeletPasses = int(v); }},
    {"bvh-treelet-min", "BVH: smallest subtree restructured, in triangles (bvh: 8)", isBoxBvh, 1, 1e9, false, true,
     "", [](AccelSpec& s, double v) { s.bvh.treeletMinPrimitives = int(v); }},
    {"bvh-reinsert-iterations", "BVH: insertion-based optimisation iterations (default 0)", isBoxBvh, 0, 1000,
     false, true, "", [](AccelSpec& s, double v) { s.bvh.reinsertIterations = int(v); }},
    {"bvh-reinsert-batch", "BVH: share of inner nodes moved an iteration (default 0.05)", isBoxBvh, 0.001, 1.0,
     false, false, "bvh-reinsert-batch must be in [0.001, 1]",
     [](AccelSpec& s, double v) { s.bvh.reinsertBatch = v; }},
    {"kd-traversal-cost", "kd-tree SAH: cost of a traversal step", isKd, 0.0, 1e9, true, false,
     "kd-traversal-cost and kd-intersection-cost must be finite and not negative",
     [](AccelSpec& s, double v) { s.kd.traversalCost = v; }},
    {"kd-intersection-cost", "kd-tree SAH: cost of a triangle test", isKd, 0.0, 1e9, true, false,
     "kd-traversal-cost and kd-intersection-cost must be finite and not negative",
     [](AccelSpec& s, double v) { s.kd.intersectionCost = v; }},
    {"kd-empty-bonus", "kd-tree SAH: bonus for cutting off empty space", isKd, 0.0, 1.0, false, false,
     "kd-empty-bonus must be in [0, 1]", [](AccelSpec& s, double v) { s.kd.emptyBonus = v; }},
    {"kd-empty-min", "kd-tree SAH: least empty share for the bonus (default 0.1)",
     isKd, 0.0, 1.0, false, false, "kd-empty-min must be in [0, 1]",
     [](AccelSpec& s, double v) { s.kd.emptyBonusMinFraction = v; }},
    {"kd-max-depth", "kd-tree: maximum depth (default 8 + 1.3 log2 N)", isKd, 1, kd::KdConfig::kMaxDepthLimit,
     false, true, "", [](AccelSpec& s, double v) { s.kd.maxDepth = int(v); }},
    {"kd-max-duplication", "kd-tree: most references a triangle (default 8)", isKd, 1.0, 1e9,
     false, false, "kd-max-duplication must be a number of references per triangle, 1 or more",
     [](AccelSpec& s, double v) { s.kd.maxDuplication = v; }},
    {"kd-short-stack", "kd-shortstack: entries of its stack (default 4)", isKdShortStack, 1, VKRAY_KD_STACK_SIZE,
     false, true, "", [](AccelSpec& s, double v) { s.kdShortStack = int(v); }},
    {"rq-fast-build", "rayquery: 1 = fast build, 0 = fast trace (default 0)", isDriver, 0,
     1, false, true, "", [](AccelSpec& s, double v) { s.driver.preferFastBuild = v != 0.0; }},
    {"rq-compact", "rayquery: 1 = compacted after its build (default 1)", isDriver, 0, 1, false, true,
     "", [](AccelSpec& s, double v) { s.driver.compact = v != 0.0; }},
};

bool accepts(const TuningOption& o, double v) {
    const bool below = o.hiOpen ? v < o.hi : v <= o.hi;
    return v >= o.lo && below && (!o.integer || v == std::floor(v));  // NaN fails every comparison
}

std::string joined(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

// The spec an accelerator's row names, before any tuning.
AccelSpec specOf(const AccelEntry& e) {
    AccelSpec spec;
    spec.name = std::string(e.name);
    spec.family = e.family;
    spec.bvh = e.bvh;
    spec.kdTraversal = e.kdTraversal;
    spec.bvhWalk = e.bvhWalk;
    return spec;
}

// "kd-max-depth applies to kd-restart, kd-pushdown, kd-backtrack, kd-stack, kd-shortstack, kd-packet only".
std::string notApplicable(const TuningOption& o) {
    std::vector<std::string> names;
    for (const AccelEntry& e : kAccels)
        if (o.appliesTo(specOf(e))) names.push_back(std::string(e.name));
    return std::string(o.name) + " applies to " + joined(names) + " only";
}

std::vector<std::string> tuningNames() {
    std::vector<std::string> names;
    for (const TuningOption& o : kTuning) names.push_back(std::string(o.name));
    return names;
}

// " (did you mean 'kd-ropes'?)" when a known name is near `typed`, else " (known: a, b, ...)".
std::string nearestOrKnown(std::string_view typed, const std::vector<std::string>& known) {
    if (const std::optional<std::string> near = closestName(typed, known)) return " (did you mean '" + *near + "'?)";
    return " (known: " + joined(known) + "; see --accel help)";
}

// The tuning written into the name after its first ':' ("bvh:aac-delta=8:..."), by option.
std::map<const TuningOption*, double> namedTuning(std::string_view text, const std::function<Error(std::string)>& fail) {
    std::map<const TuningOption*, double> tuning;
    for (size_t at = text.find(':'); at != std::string_view::npos;) {
        const size_t end = text.find(':', at + 1);
        const std::string_view item = text.substr(at + 1, end == std::string_view::npos ? end : end - at - 1);
        at = end;
        const size_t eq = item.find('=');
        std::string_view key = item.substr(0, eq);
        if (key.starts_with("--")) key.remove_prefix(2);
        if (eq == std::string_view::npos || key.empty())
            throw fail("expected OPTION=VALUE after ':', got '" + std::string(item) + "'");
        const auto option = std::find_if(std::begin(kTuning), std::end(kTuning),
                                         [&](const TuningOption& o) { return o.name == key; });
        if (option == std::end(kTuning))
            throw fail("unknown tuning option '" + std::string(key) + "'" + nearestOrKnown(key, tuningNames()));
        double v = 0.0;  // the scene files' number rule: whole token, locale-independent, finite
        if (parseReal(item.substr(eq + 1), v) != NumberStatus::Ok)
            throw fail("'" + std::string(item) + "': the value is not a number");
        if (!tuning.emplace(&*option, v).second) throw fail(std::string(key) + " is given twice");
    }
    return tuning;
}

// "1..1024", "[0, 0.5)", ">= 1": what accepts() lets through, for `--accel help`.
std::string valueRange(const TuningOption& o) {
    if (o.hi >= 1e9) return std::string(o.integer ? "INT" : "X") + " >= " + shortNumber(o.lo);
    if (o.integer) return shortNumber(o.lo) + ".." + shortNumber(o.hi);
    std::string range = "[";
    range.append(shortNumber(o.lo)).append(", ").append(shortNumber(o.hi)).append(o.hiOpen ? ")" : "]");
    return range;
}

}  // namespace

const std::vector<std::string>& accelNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const AccelEntry& e : kAccels) n.push_back(std::string(e.name));
        return n;
    }();
    return names;
}

std::span<const TuningOption> tuningOptions() { return kTuning; }

AccelSpec resolveAccel(std::string_view text) {
    const auto fail = [&](const std::string& why) { return Error("--accel " + std::string(text) + ": " + why); };
    const std::string_view name = text.substr(0, text.find(':'));
    const auto entry = std::find_if(std::begin(kAccels), std::end(kAccels),
                                    [&](const AccelEntry& e) { return e.name == name; });
    if (entry == std::end(kAccels))
        throw fail("unknown accelerator '" + std::string(name) + "'" + nearestOrKnown(name, accelNames()));
    AccelSpec spec = specOf(*entry);
    spec.name = std::string(text);
    // In the table's order, whatever the text's: the options touch separate fields.
    for (const auto& [option, value] : namedTuning(text, fail)) {
        if (!accepts(*option, value)) {
            const std::string rule = option->rule.empty() ? std::string(option->name) + " must be " +
                                                                shortNumber(option->lo) + ".." + shortNumber(option->hi)
                                                          : std::string(option->rule);
            throw fail(rule + " (got " + shortNumber(value) + ")");
        }
        if (!option->appliesTo(spec)) throw fail(notApplicable(*option));
        option->apply(spec, value);
    }
    return spec;
}

std::string accelHelp() {
    std::string text = "accelerators (--accel NAME, default " + std::string(kDefaultAccel) + "):\n", line = " ";
    for (const std::string& name : accelNames()) {
        if (line.size() + name.size() > 94) {
            text.append(line).append("\n");
            line.assign(1, ' ');
        }
        line += " " + name;
    }
    text += line + "\ntuning follows the name: --accel NAME:OPTION=VALUE[:OPTION=VALUE...], "
                   "e.g. --accel bvh:aac-delta=8\n";
    for (const TuningOption& o : kTuning) {
        char row[256];
        std::snprintf(row, sizeof row, "  %-24s %-12s %s\n", std::string(o.name).c_str(), valueRange(o).c_str(),
                      std::string(o.help).c_str());
        text += row;
    }
    return text;
}

std::string structureKey(const AccelSpec& spec) {
    switch (spec.family) {
    case Family::Brute: return "brute";
    case Family::Driver:
        return std::string("driver ") + (spec.driver.preferFastBuild ? "fast-build" : "fast-trace") +
               (spec.driver.compact ? " compacted" : "");
    case Family::Bvh: return "bvh " + spec.bvh.describe();
    case Family::Kd:  // one tree for every kd traversal; kd-ropes adds its ropes to it
        return "kd " + spec.kd.describe() + " depth " + (spec.kd.maxDepth ? std::to_string(*spec.kd.maxDepth) : "auto") +
               " duplication " + shortNumber(spec.kd.maxDuplication) +
               (spec.kdTraversal == kd::Traversal::Ropes ? " with ropes" : "");
    }
    return spec.name;
}

}  // namespace vkray::accel
