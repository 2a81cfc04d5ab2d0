// A bench run that stops early and `--resume` (bench_resume.h): the incomplete report says what it
// lacks in all three files and keeps its pictures' pixels; a resumed run refuses another run's
// report, keeps the finished scenes as they were measured and measures only the others; a scene
// that does not load is refused before anything is measured. Times are never compared, only copied.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/bench_json.h"
#include "bench/bench_resume.h"
#include "bench/bench_runner.h"
#include "bench/report.h"
#include "core/error.h"
#include "render/device.h"
#include "report_fixture.h"

namespace vkray::bench {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

const fs::path kRoot = fs::path(VKRAY_TEST_OUTPUT_DIR) / ("bench-resume-" + std::to_string(getpid()));

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The fixture's two scenes as the first two of a run of three, stopped by a signal.
BenchResults stoppedRun() {
    BenchResults r = fixture::results();
    r.settings.scenes = {"scenes/alpha.scene", "scenes/beta.scene", "scenes/gamma.scene"};
    r.settings.accels = {"bvh"};
    r.settings.repeat = 3;
    r.settings.threads = {1, 2};
    r.settings.deltas = {};
    r.settings.maxDepthSweep = false;
    for (size_t i = 0; i < r.scenes.size(); ++i) r.scenes[i].index = int(i);
    r.failure = "interrupted by SIGTERM";
    return r;
}

size_t filesWithExtension(const fs::path& dir, const std::string& ext) {
    return size_t(std::count_if(fs::directory_iterator(dir), fs::directory_iterator(),
                                [&](const fs::directory_entry& e) { return e.path().extension() == ext; }));
}

TEST(BenchIncomplete, EveryFileSaysWhyAndWhichScenesAreMissing) {
    const BenchResults r = stoppedRun();
    EXPECT_EQ(missingScenes(r), std::vector<std::string>{"scenes/gamma.scene"});
    const Json j = Json::parse(benchJson(r));
    EXPECT_EQ(j["complete"], false);
    EXPECT_EQ(j["failure"], "interrupted by SIGTERM");
    EXPECT_EQ(j["missing_scenes"], Json::array({"scenes/gamma.scene"}));
    const std::string notice = incompleteNotice(r);
    EXPECT_NE(notice.find("interrupted by SIGTERM"), std::string::npos);
    EXPECT_NE(notice.find("Not measured: scenes/gamma.scene"), std::string::npos);
    EXPECT_NE(notice.find("--resume"), std::string::npos);
    EXPECT_NE(benchMarkdown(r).find("> **Incomplete:** the run stopped before it finished: interrupted by SIGTERM"),
              std::string::npos);
    EXPECT_NE(benchHtml(r).find("<p class=\"incomplete\"><strong>Incomplete:</strong> the run stopped"), std::string::npos);

    BenchResults done = r;
    done.failure.clear();
    EXPECT_TRUE(missingScenes(done).empty());
    const Json k = Json::parse(benchJson(done));
    EXPECT_EQ(k["complete"], true);
    EXPECT_TRUE(k["failure"].is_null());
    EXPECT_EQ(k["missing_scenes"], Json::array());
    EXPECT_EQ(benchMarkdown(done).find("Incomplete"), std::string::npos);
    EXPECT_EQ(benchHtml(done).find("class=\"incomplete\""), std::string::npos);
}

TEST(BenchIncomplete, KeepsPixelsForResumeAndDropsThemWhenComplete) {
    const fs::path dir = kRoot / "pixels";
    fs::remove_all(dir);
    const BenchResults r = stoppedRun();
    writeBenchReport(r, dir);
    EXPECT_GT(filesWithExtension(dir / "images", ".pfm"), 0u);
    const BenchResults back = readBenchReport(dir);
    EXPECT_EQ(back.failure, r.failure);
    ASSERT_EQ(back.scenes.size(), 2u);
    EXPECT_EQ(back.scenes[0].reference.data, r.scenes[0].reference.data);
    EXPECT_EQ(back.scenes[0].accels[0].image.data, r.scenes[0].accels[0].image.data);
    EXPECT_EQ(back.scenes[0].accels[0].nodesPerPixel, r.scenes[0].accels[0].nodesPerPixel);

    BenchResults done = back;
    done.failure.clear();
    writeBenchReport(done, dir);
    EXPECT_EQ(filesWithExtension(dir / "images", ".pfm"), 0u);
    EXPECT_TRUE(readBenchReport(dir).complete());
    fs::remove_all(dir);
}

TEST(BenchIncomplete, ReportWithoutTheFieldsReadsAsComplete) {
    const fs::path dir = kRoot / "old";
    fs::remove_all(dir);
    BenchResults r = stoppedRun();
    r.failure.clear();
    writeBenchReport(r, dir);
    Json j = Json::parse(readText(dir / "bench.json"));
    j.erase("complete");
    j.erase("failure");
    j.erase("missing_scenes");
    std::ofstream(dir / "bench.json") << j.dump(2);
    EXPECT_TRUE(readBenchReport(dir).complete());
    fs::remove_all(dir);
}

std::string resumeError(const BenchResults& previous, const BenchResults& run) {
    try {
        checkResumable(previous, run, "out/bench.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "(resumable)";
}

TEST(BenchResume, RefusesTheReportOfAnotherRun) {
    const BenchResults previous = stoppedRun();
    BenchResults run = previous;
    run.scenes.clear();
    run.failure.clear();
    EXPECT_EQ(resumeError(previous, run), "(resumable)");

    BenchResults other = run;
    other.settings.repeat = 5;
    EXPECT_NE(resumeError(previous, other).find("out/bench.json: --resume: other settings: repeat is 3 here, 5 in this run; "
                                                "to start afresh"),
              std::string::npos);
    other = run;
    other.settings.width = 64;
    EXPECT_NE(resumeError(previous, other).find("other settings: width is 0 here, 64"), std::string::npos);
    other = run;
    other.settings.accels = {"bvh", "kd-stack"};
    EXPECT_NE(resumeError(previous, other).find("other settings: accels"), std::string::npos);
    other = run;
    other.revision = "def5678";
    EXPECT_NE(resumeError(previous, other).find("written by vkray 0.1.0 (revision abc1234), this is vkray 0.1.0 "
                                                "(revision def5678)"),
              std::string::npos);
    other = run;
    other.device = "NVIDIA H200";
    EXPECT_NE(resumeError(previous, other).find("measured on llvmpipe"), std::string::npos);
    other = run;
    other.shard = {1, 2};
    EXPECT_NE(resumeError(previous, other).find("measured shard 0/1, this run is shard 1/2"), std::string::npos);
    BenchResults merged = previous;
    merged.shards.push_back({});
    EXPECT_NE(resumeError(merged, run).find("a merged report"), std::string::npos);
}

TEST(BenchResume, NothingToResumeInAFolderWithoutReport) {
    fs::create_directories(kRoot / "empty");
    EXPECT_FALSE(readResumableReport(kRoot / "empty").has_value());
}

// ---- Real runs on lavapipe ------------------------------------------------------------------

class BenchResumeRun : public ::testing::Test {
protected:
    void SetUp() override {
        const char* dev = std::getenv("VKRAY_TEST_DEVICE");
        device_.emplace(gpu::ContextOptions{.validation = true, .device = dev ? dev : ""});
        options_.scenes = {std::string(VKRAY_SOURCE_DIR) + "/tests/cli/data/one_triangle.scene",
                           std::string(VKRAY_SOURCE_DIR) + "/scenes/objects.scene"};
        options_.accels = {"bvh"};
        options_.width = 16;
        options_.height = 12;
        options_.repeat = 1;
        options_.threads = {1};
        options_.deltas = {};
        options_.maxDepthSweep = false;
    }
    std::optional<render::Device> device_;
    BenchOptions options_;
};

// The run fails as scene 2 starts (a progress callback that throws stands for a render the device
// cuts short): scene 1's results are saved, marked with the failure; the resumed run loads them and
// measures scene 2 alone.
TEST_F(BenchResumeRun, SavesFinishedScenesAndResumeMeasuresOnlyTheRest) {
    const fs::path dir = kRoot / "run";
    fs::remove_all(dir);
    BenchContinuation first;
    first.save = [&](const BenchResults& r) { writeBenchReport(r, dir); };
    const auto failAtSceneTwo = [](const BenchProgress& p) {
        if (p.scene == 2) throw Error("the device cut a render short");
    };
    EXPECT_THROW(runBench(*device_, options_, "first", failAtSceneTwo, first), Error);
    const std::optional<BenchResults> saved = readResumableReport(dir);
    ASSERT_TRUE(saved.has_value());
    EXPECT_EQ(saved->failure, "the device cut a render short");
    ASSERT_EQ(saved->scenes.size(), 1u);
    EXPECT_EQ(saved->scenes[0].index, 0);
    EXPECT_EQ(missingScenes(*saved), std::vector<std::string>{options_.scenes[1]});
    ASSERT_EQ(saved->scenes[0].accels.size(), 1u);
    EXPECT_GT(saved->scenes[0].reference.width, 0);  // its pixels, for the resumed report

    std::vector<int> measured;
    BenchContinuation resume;
    resume.previous = &*saved;
    const BenchResults r = runBench(*device_, options_, "resume",
                                    [&](const BenchProgress& p) { measured.push_back(p.scene); }, resume);
    EXPECT_TRUE(r.complete());
    EXPECT_FALSE(measured.empty());
    EXPECT_TRUE(std::all_of(measured.begin(), measured.end(), [](int s) { return s == 2; }));
    ASSERT_EQ(r.scenes.size(), 2u);
    EXPECT_EQ(r.scenes[0].index, 0);
    EXPECT_EQ(r.scenes[1].index, 1);
    // Scene 1 as the first run measured it, not measured again.
    EXPECT_EQ(r.scenes[0].accels[0].traceMs.median, saved->scenes[0].accels[0].traceMs.median);
    EXPECT_EQ(r.scenes[0].referenceRenderMs, saved->scenes[0].referenceRenderMs);
    EXPECT_EQ(r.scenes[0].reference.data, saved->scenes[0].reference.data);
    EXPECT_EQ(r.scenes[1].configurations.size(), saved->scenes[0].configurations.size());
    EXPECT_EQ(r.startedAt, saved->startedAt);

    // The same report with other settings is refused before anything is measured.
    BenchOptions other = options_;
    other.repeat = 2;
    measured.clear();
    try {
        runBench(*device_, other, "other", [&](const BenchProgress& p) { measured.push_back(p.scene); }, resume);
        ADD_FAILURE() << "resumed another run";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("other settings: repeat is 1 here, 2 in this run"), std::string::npos);
    }
    EXPECT_TRUE(measured.empty());
    fs::remove_all(dir);
}

// Every scene is loaded before the first is measured: a mesh that cannot be read in scene 2 fails
// the run before scene 1 is measured, and nothing is saved.
TEST_F(BenchResumeRun, UnreadableMeshRefusedBeforeMeasuring) {
    fs::create_directories(kRoot);
    const fs::path scene = kRoot / "missing_mesh.scene";
    std::ofstream(scene) << "camera 0 0 5  0 0 0  0 1 0  45\nsize 16 12\ngeo no_such_mesh.obj\n";
    options_.scenes[1] = scene.string();
    bool progressed = false, saved = false;
    BenchContinuation c;
    c.save = [&](const BenchResults&) { saved = true; };
    try {
        runBench(*device_, options_, "refused", [&](const BenchProgress&) { progressed = true; }, c);
        ADD_FAILURE() << "a scene with a missing mesh was measured";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("missing_mesh.scene:3"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(progressed);
    EXPECT_FALSE(saved);
}

}  // namespace
}  // namespace vkray::bench
