// The accelerator registry: every `--accel` name (README.md, "Accelerators") resolves to the family
// and traversal it names, with its preset and the tuning options checked; an unknown name is an
// error that lists the known ones; and every accelerator built over the same scene answers like
// brute force through the common BuiltAccel interface. And asBytes, which every structure's GPU
// arrays pass through, copies arrays of any size exactly.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "accel/accel.h"
#include "soup_test_util.h"
#include "core/error.h"
#include "geometry/brute_force.h"

namespace vkray::accel {
namespace {

TEST(Accel, EveryNameResolvesToItsFamilyAndTraversal) {
    for (const std::string name :
         {"bvh", "bvh-fast", "bvh-hq", "bvh-stackless", "bvh-packet", "bvh-sphere", "kd-restart", "kd-pushdown", "kd-ropes", "kd-backtrack", "kd-stack", "kd-shortstack", "kd-packet",
          "brute"})
        EXPECT_NE(std::find(accelNames().begin(), accelNames().end(), name), accelNames().end()) << name;
    EXPECT_EQ(resolveAccel("brute").family, Family::Brute);
    EXPECT_EQ(resolveAccel("bvh-hq").family, Family::Bvh);
    EXPECT_EQ(resolveAccel("bvh-sah").bvh.builder, bvh::Config::Builder::BinnedSah);
    EXPECT_EQ(resolveAccel("bvh").bvh.builder, bvh::Config::Builder::Aac);
    EXPECT_EQ(resolveAccel("kd-stack").kdTraversal, kd::Traversal::Stack);
    EXPECT_EQ(resolveAccel("kd-restart").kdTraversal, kd::Traversal::Restart);
    EXPECT_EQ(resolveAccel("kd-backtrack").kdTraversal, kd::Traversal::Backtrack);
    EXPECT_EQ(resolveAccel("kd-pushdown").kdTraversal, kd::Traversal::PushDown);
    EXPECT_EQ(resolveAccel("kd-ropes").kdTraversal, kd::Traversal::Ropes);
    EXPECT_EQ(resolveAccel("kd-shortstack").kdTraversal, kd::Traversal::ShortStack);
    EXPECT_EQ(resolveAccel("kd-shortstack").kdShortStack, VKRAY_KD_SHORT_STACK_SIZE);
    EXPECT_EQ(resolveAccel("kd-shortstack:kd-short-stack=2").kdShortStack, 2);
    EXPECT_EQ(resolveAccel("kd-backtrack").family, Family::Kd);
    EXPECT_EQ(resolveAccel(kDefaultAccel).name, "bvh");
}

std::string resolveError(const std::string& text) {
    try {
        resolveAccel(text);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(Accel, UnknownNameListsTheKnownOnes) {
    const std::string what = resolveError("octree");
    EXPECT_NE(what.find("octree"), std::string::npos) << what;
    EXPECT_NE(what.find("kd-backtrack"), std::string::npos) << what;
}

// A name near a known one is answered with that one, not the whole list.
TEST(Accel, MistypedNamesGetTheNearestOne) {
    EXPECT_EQ(resolveError("kd-rope"), "--accel kd-rope: unknown accelerator 'kd-rope' (did you mean 'kd-ropes'?)");
    EXPECT_EQ(resolveError("bhv-fast"), "--accel bhv-fast: unknown accelerator 'bhv-fast' (did you mean 'bvh-fast'?)");
    EXPECT_EQ(resolveError("bvh:aac-delt=8"),
              "--accel bvh:aac-delt=8: unknown tuning option 'aac-delt' (did you mean 'aac-delta'?)");
    EXPECT_EQ(resolveError("kd-stack:kd-maxdepth=8"),
              "--accel kd-stack:kd-maxdepth=8: unknown tuning option 'kd-maxdepth' (did you mean 'kd-max-depth'?)");
}

// `--accel help` lists every accelerator and every tuning option with its values.
TEST(Accel, HelpListsNamesAndOptions) {
    const std::string help = accelHelp();
    for (const std::string& name : accelNames()) EXPECT_NE(help.find(name), std::string::npos) << name;
    for (const TuningOption& o : tuningOptions()) EXPECT_NE(help.find(std::string(o.name)), std::string::npos) << o.name;
    EXPECT_NE(help.find("aac-delta                1..1024"), std::string::npos) << help;
    EXPECT_NE(help.find("aac-epsilon              [0, 0.5)"), std::string::npos) << help;
}

TEST(AccelSpec, PresetsAndOverrides) {
    EXPECT_EQ(resolveAccel("bvh-fast").bvh.delta, 4);
    EXPECT_DOUBLE_EQ(resolveAccel("bvh-fast").bvh.epsilon, 0.2);
    EXPECT_EQ(resolveAccel("bvh-hq").bvh.delta, 20);
    const AccelSpec tuned = resolveAccel("bvh-hq:aac-delta=9:aac-epsilon=0.25");
    EXPECT_EQ(tuned.bvh.delta, 9);
    EXPECT_DOUBLE_EQ(tuned.bvh.epsilon, 0.25);
    EXPECT_THROW(resolveAccel("bvh-hq:aac-epsilon=0.7"), Error);
    EXPECT_THROW(resolveAccel("bvh-sah:aac-delta=3"), Error);  // the binned-SAH builder has no delta
    const AccelSpec kd = resolveAccel("kd-stack:kd-max-depth=56:kd-empty-bonus=0");
    EXPECT_EQ(kd.kd.maxDepth, 56);
    EXPECT_EQ(kd.kd.emptyBonus, 0.0);
    EXPECT_FALSE(resolveAccel("kd-stack").kd.maxDepth.has_value());
}

// Each tuning option is refused outside its range, for a non-integer where it counts whole things,
// and for an accelerator it does not tune; the error names the option.
TEST(AccelSpec, EveryTuningOptionIsRangeCheckedAndNamed) {
    const auto expectError = [](const std::string& accel, const std::string& option, const std::string& value,
                                const std::string& words) {
        const std::string what = resolveError(accel + ":" + option + "=" + value);
        EXPECT_NE(what.find(option), std::string::npos) << what;
        EXPECT_NE(what.find(words), std::string::npos) << what;
    };
    expectError("bvh", "aac-delta", "0", "must be 1..1024");
    expectError("bvh", "aac-delta", "1025", "must be 1..1024");
    expectError("bvh", "aac-delta", "4.5", "must be 1..1024");
    expectError("bvh", "aac-epsilon", "0.5", "must be in [0, 0.5)");
        expectError("kd-restart", "kd-traversal-cost", "-1", "must be finite and not negative");
    expectError("kd-restart", "kd-intersection-cost", "1e10", "must be finite and not negative");
    expectError("kd-restart", "kd-empty-bonus", "1.5", "must be in [0, 1]");
    expectError("kd-restart", "kd-empty-min", "-0.1", "must be in [0, 1]");
    // The kd-stack kernel's stack bounds the depth: the limit the command line accepts is the one the
    // builder honours, not silently clamped.
    expectError("kd-restart", "kd-max-depth", "57", "must be 1..56");
    expectError("kd-restart", "kd-max-depth", "0", "must be 1..56");
    expectError("bvh", "kd-max-depth", "10", "applies to kd-restart, kd-pushdown, kd-ropes, kd-backtrack, kd-stack, kd-shortstack, kd-packet only");
    expectError("kd-stack", "aac-delta", "8", "applies to bvh, bvh-fast, bvh-hq, bvh-stackless, bvh-packet, bvh-sphere only");
    // Treelet restructuring prices boxes.
    expectError("bvh-sphere", "bvh-treelet-passes", "2", "applies to bvh, bvh-fast, bvh-hq, bvh-sah, bvh-stackless, bvh-packet only");
    expectError("bvh-sphere", "bvh-reinsert-iterations", "2", "applies to bvh, bvh-fast, bvh-hq, bvh-sah, bvh-stackless, bvh-packet only");
    expectError("bvh", "bvh-reinsert-iterations", "1001", "must be 0..1000");
    expectError("bvh", "bvh-reinsert-batch", "0", "must be in [0.001, 1]");
    expectError("bvh", "bvh-reinsert-batch", "1.5", "must be in [0.001, 1]");
    expectError("brute", "kd-empty-bonus", "0.5", "applies to");
    for (const TuningOption& o : tuningOptions()) EXPECT_NE(o.name.substr(0, 1), "-") << o.name;
}

// Tuning written after the name (with or without the dashes of an option), the whole text as the
// name, and every malformed, unknown, repeated or inapplicable option refused with the text in the message.
TEST(AccelSpec, TuningAfterTheName) {
    const AccelSpec named = resolveAccel("bvh:bvh-reinsert-iterations=20:--bvh-reinsert-batch=0.1");
    EXPECT_EQ(named.name, "bvh:bvh-reinsert-iterations=20:--bvh-reinsert-batch=0.1");
    EXPECT_EQ(named.bvh.reinsertIterations, 20);
    EXPECT_DOUBLE_EQ(named.bvh.reinsertBatch, 0.1);
    EXPECT_EQ(structureKey(named), structureKey(resolveAccel("bvh:bvh-reinsert-batch=0.1:bvh-reinsert-iterations=20")));
    EXPECT_NE(structureKey(named), structureKey(resolveAccel("bvh")));
    EXPECT_EQ(resolveAccel("kd-stack:kd-max-depth=12").kd.maxDepth, 12);
    const auto expectError = [](const std::string& text, const std::string& words) {
        const std::string what = resolveError(text);
        EXPECT_NE(what.find("--accel " + text + ": "), std::string::npos) << what;
        EXPECT_NE(what.find(words), std::string::npos) << what;
    };
    expectError("bvh:", "expected OPTION=VALUE after ':'");
    expectError("bvh:aac-delta", "expected OPTION=VALUE after ':', got 'aac-delta'");
    expectError("bvh:=3", "expected OPTION=VALUE");
    expectError("bvh:octree-depth=3", "unknown tuning option 'octree-depth' (known: aac-delta,");
    expectError("bvh:aac-delta=8x", "'aac-delta=8x': the value is not a number");
    expectError("bvh:aac-delta=", "the value is not a number");
    expectError("bvh:aac-epsilon=nan", "'aac-epsilon=nan': the value is not a number");
    expectError("bvh:aac-delta=8:aac-delta=9", "aac-delta is given twice");
    expectError("bvh:aac-delta=8:--aac-delta=9", "aac-delta is given twice");
    expectError("bvh:aac-delta=2000", "aac-delta must be 1..1024 (got 2000)");
    expectError("kd-stack:aac-delta=8", "aac-delta applies to bvh, bvh-fast, bvh-hq, bvh-stackless, bvh-packet, bvh-sphere only");
    expectError("octree:aac-delta=8", "unknown accelerator 'octree'");
}

TEST(AccelSpec, StructureKeysTellWhichBuildsAreShared) {
    EXPECT_NE(structureKey(resolveAccel("bvh")), structureKey(resolveAccel("bvh-hq")));
    EXPECT_EQ(structureKey(resolveAccel("bvh")),
              structureKey(resolveAccel("bvh-hq:bvh-treelet-passes=2:bvh-treelet-min=8")));
    EXPECT_NE(structureKey(resolveAccel("bvh")), structureKey(resolveAccel("bvh:bvh-treelet-passes=3")));
    const AccelSpec reinserted = resolveAccel("bvh:bvh-reinsert-iterations=10");
    EXPECT_NE(structureKey(resolveAccel("bvh")), structureKey(reinserted));
    EXPECT_NE(structureKey(reinserted),
              structureKey(resolveAccel("bvh:bvh-reinsert-iterations=10:bvh-reinsert-batch=0.5")));
    EXPECT_NE(structureKey(resolveAccel("bvh")), structureKey(resolveAccel("bvh-fast")));
    EXPECT_NE(structureKey(resolveAccel("bvh-sah")), structureKey(resolveAccel("bvh-fast")));
    EXPECT_EQ(structureKey(resolveAccel("kd-stack")), structureKey(resolveAccel("kd-backtrack")));
    EXPECT_NE(structureKey(resolveAccel("kd-stack")), structureKey(resolveAccel("kd-ropes")));  // plus its ropes
    EXPECT_NE(structureKey(resolveAccel("kd-stack")),
              structureKey(resolveAccel("kd-stack:kd-intersection-cost=5")));
    EXPECT_NE(structureKey(resolveAccel("kd-stack")), structureKey(resolveAccel("kd-stack:kd-max-depth=9")));
    EXPECT_NE(structureKey(resolveAccel("kd-stack")), structureKey(resolveAccel("kd-stack:kd-empty-min=0")));
    EXPECT_NE(structureKey(resolveAccel("kd-stack")),
              structureKey(resolveAccel("kd-stack:kd-max-duplication=4")));
}


// Every accelerator through the one interface the renderers use: same closest triangle and t as
// brute force, same any-hit answer, and a triangle order that is a permutation when given.
class EveryAccel : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryAccel, AnswersLikeBruteForce) {
    const Scene scene = test::smallSoup(600, 7);
    const auto built = buildAccel(scene, resolveAccel(GetParam()), BuildOptions{.threads = 2, .progress = {}});
    const auto tracer = built->makeTracer(scene);
    const geometry::BruteForceTracer brute(scene);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int hits = 0;
    for (int k = 0; k < 2000; ++k) {
        // From outside or inside the soup towards a point in it: most rays meet something.
        const glm::dvec3 origin{u(rng) * 3.0, u(rng) * 3.0, u(rng) * 3.0};
        const glm::dvec3 target{u(rng), u(rng), u(rng)};
        const geometry::Ray ray{origin, glm::normalize(target - origin)};
        const geometry::Hit want = brute.closest(ray, 1e30), got = tracer->closest(ray, 1e30);
        ASSERT_EQ(got.triangle, want.triangle) << GetParam() << " ray " << k;
        if (want.found()) {
            ++hits;
            EXPECT_NEAR(got.t, want.t, 1e-9 * want.t);
        }
        EXPECT_EQ(tracer->occluded(ray, 1.5), brute.occluded(ray, 1.5)) << GetParam() << " ray " << k;
    }
    EXPECT_GT(hits, 1000);  // the rays do meet the soup

    const GpuAccelData gpu = built->gpuData();
    if (!gpu.triangleOrder.empty()) {
        std::vector<uint32_t> sorted = gpu.triangleOrder;
        std::sort(sorted.begin(), sorted.end());
        for (uint32_t k = 0; k < sorted.size(); ++k) ASSERT_EQ(sorted[k], k);
        EXPECT_EQ(sorted.size(), scene.triangles.size());
    }
}

INSTANTIATE_TEST_SUITE_P(Names, EveryAccel, ::testing::ValuesIn(accelNames()),
                         [](const auto& info) {
                             std::string n = info.param;
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n;
                         });

// Beyond kFirstTouchBytes asBytes populates its copy's pages in parallel before copying: the bytes
// must still be the array's, to the last one (an odd length, not a whole number of pages).
TEST(AsBytes, CopiesLargeArraysExactly) {
    std::vector<uint32_t> words(3 * (size_t(1) << 20) + 5);  // 12 MiB and 20 bytes
    std::iota(words.begin(), words.end(), 7u);
    const std::vector<std::byte> bytes = asBytes(words);
    ASSERT_EQ(bytes.size(), words.size() * sizeof(uint32_t));
    EXPECT_EQ(std::memcmp(bytes.data(), words.data(), bytes.size()), 0);
    EXPECT_TRUE(asBytes(std::vector<uint32_t>{}).empty());
}

}  // namespace
}  // namespace vkray::accel
