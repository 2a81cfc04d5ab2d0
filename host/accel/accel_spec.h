// Which acceleration structure a render uses, and how it is built: `--accel NAME[:OPTION=VALUE...]`
// resolved once, in resolveAccel(), into a typed AccelSpec whose configs are validated.
//
// accel_spec.cpp holds the only two tables: the accelerators (name, family, preset) and the tuning
// options (name, help, the accelerators it applies to, accepted range, the config field it sets).
// A new accelerator is a row of the first (plus its builder and kernel), a new tuning option a row
// of the second (plus the config field); `--accel help`, the errors and their suggestions follow.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "accel/bvh/bvh.h"
#include "accel/kd/kd_tree.h"
#include "shared/kd_layout.h"

namespace vkray::accel {

// Driver: the device's own ray tracing (`rayquery`), whose structure the driver builds on the device.
enum class Family { Brute, Bvh, Kd, Driver };

// How the driver builds `rayquery`'s structure (VkBuildAccelerationStructureFlagsKHR): for a fast
// trace or a fast build, and compacted after the build (a copy into the size the driver reports).
struct DriverBuild {
    bool preferFastBuild = false;
    bool compact = true;
};

// How a BVH kernel walks the tree (one tree for all three): a stack per ray; parent links instead
// (Hapala et al. 2011); or one stack for the rays of a subgroup, walked together as a packet
// (Günther et al. 2007; shaders/include/bvh_packet.glsl).
enum class BvhWalk { Stack, Stackless, Packet };

// The accelerator `vkray render` uses when --accel is not given.
inline constexpr std::string_view kDefaultAccel = "bvh";

struct AccelSpec {
    std::string name{kDefaultAccel};  // as given on the command line ("bvh-hq")
    Family family = Family::Bvh;
    bvh::Config bvh = bvh::Config::aacHq();  // Family::Bvh: the preset with any overrides
    BvhWalk bvhWalk = BvhWalk::Stack;        // Family::Bvh: how its kernel walks the tree (same tree)
    kd::KdConfig kd;                         // Family::Kd: the defaults with any overrides
    kd::Traversal kdTraversal = kd::Traversal::Restart;  // Family::Kd: the same tree for all of them
    // kd-shortstack: its stack's entries (a specialization constant of its kernel, not part of the
    // structure: files of any size serve).
    int kdShortStack = VKRAY_KD_SHORT_STACK_SIZE;
    DriverBuild driver;  // Family::Driver
};

// Every accelerator name vkray accepts, in the order `--help` lists them.
const std::vector<std::string>& accelNames();

// One tuning option (for example aac-delta in `--accel bvh:aac-delta=8`), as accel_spec.cpp defines it.
struct TuningOption {
    std::string_view name;  // "aac-delta"
    std::string_view help;  // for `--accel help`
    // Whether it changes the structure `spec` builds, or how its kernel walks it; given for one it does
    // not, it is an error.
    bool (*appliesTo)(const AccelSpec& spec);
    // Accepted values: lo <= v <= hi (v < hi when hiOpen), whole numbers only when `integer`.
    double lo, hi;
    bool hiOpen, integer;
    // The error, in a sentence ("aac-epsilon must be in [0, 0.5)"); empty: "NAME must be LO..HI".
    std::string_view rule;
    void (*apply)(AccelSpec& spec, double value);
};

std::span<const TuningOption> tuningOptions();

// The spec for an accelerator's name, with the tuning that may follow it, so that one list compares
// a preset with variants of it: "bvh:bvh-reinsert-iterations=20:bvh-reinsert-batch=0.1" is bvh with
// those two options (each a tuning option's name, '=', a number); the spec keeps the whole text as
// its name. Throws vkray::Error naming the text for an unknown name or option (with the nearest
// known one, core/suggest.h, else the list), a malformed option, an option given twice, a value out
// of range, or an option that does not apply to the accelerator (say kd-max-depth with bvh).
AccelSpec resolveAccel(std::string_view text);

// What `--accel help` prints: the accelerators, the syntax, and each tuning option with its values
// and the accelerators it applies to, one line each.
std::string accelHelp();

// What two specs share when they build the same structure (bvh and bvh-hq; the three kd
// traversals): equal keys mean one build serves both.
std::string structureKey(const AccelSpec& spec);

}  // namespace vkray::accel
