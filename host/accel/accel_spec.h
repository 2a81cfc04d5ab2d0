// Which acceleration structure a render uses, and how it is built: `--accel NAME` and the tuning
// options resolved once, in resolveAccel(), into a typed AccelSpec whose configs are validated.
//
// accel_spec.cpp holds the only two tables: the accelerators (name, family, preset) and the tuning
// options (flag, help, the accelerators it applies to, accepted range, the config field it sets).
// A new accelerator is a row of the first (plus its builder and kernel), a new tuning option a row
// of the second (plus the config field); the command line, its help and its errors follow.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "accel/bvh/bvh.h"
#include "accel/kd/kd_tree.h"
#include "shared/kd_layout.h"

namespace vkray::accel {

enum class Family { Brute, Bvh, Kd };

// The accelerator `vkray render` uses when --accel is not given.
inline constexpr std::string_view kDefaultAccel = "bvh";

struct AccelSpec {
    std::string name{kDefaultAccel};  // as given on the command line ("bvh-hq")
    Family family = Family::Bvh;
    bvh::Config bvh = bvh::Config::aacHq();  // Family::Bvh: the preset with any overrides
    bool bvhStackless = false;               // Family::Bvh: parent links instead of a stack (same tree)
    kd::KdConfig kd;                         // Family::Kd: the defaults with any overrides
    kd::Traversal kdTraversal = kd::Traversal::Restart;  // Family::Kd: the same tree for all of them
    // kd-shortstack: its stack's entries (a specialization constant of its kernel, not part of the
    // structure: files of any size serve).
    int kdShortStack = VKRAY_KD_SHORT_STACK_SIZE;
};

// Every accelerator name vkray accepts, in the order `--help` lists them.
const std::vector<std::string>& accelNames();

// One tuning option of the command line (for example --aac-delta), as accel_spec.cpp defines it.
struct TuningOption {
    std::string_view flag;  // "--aac-delta"
    std::string_view help;  // for --help
    // Whether it changes the structure `spec` builds, or how its kernel walks it; given for one it does
    // not, it is an error.
    bool (*appliesTo)(const AccelSpec& spec);
    // Accepted values: lo <= v <= hi (v < hi when hiOpen), whole numbers only when `integer`.
    double lo, hi;
    bool hiOpen, integer;
    // The error, in a sentence ("--aac-epsilon must be in [0, 0.5)"); empty: "FLAG must be LO..HI".
    std::string_view rule;
    void (*apply)(AccelSpec& spec, double value);
};

std::span<const TuningOption> tuningOptions();

// Tuning values by flag ("--aac-delta" -> 8); a flag that is absent or empty keeps the preset.
using Tuning = std::map<std::string, std::optional<double>, std::less<>>;

// The spec for a name with the tuning applied. The name may carry tuning of its own, so that one
// list compares a preset with variants of it: "bvh:bvh-reinsert-iterations=20:bvh-reinsert-batch=0.1"
// is bvh with those two options (each a tuning flag without its dashes, '=', a number); the spec
// keeps the whole text as its name. Throws vkray::Error naming the option for an unknown name
// (listing the known ones), an unknown or malformed option in the name, an option given twice, a
// value out of range, or an option that does not apply to the accelerator (say --kd-max-depth with bvh).
AccelSpec resolveAccel(std::string_view name, const Tuning& tuning = {});

// What two specs share when they build the same structure (bvh and bvh-hq; the three kd
// traversals): equal keys mean one build serves both.
std::string structureKey(const AccelSpec& spec);

}  // namespace vkray::accel
