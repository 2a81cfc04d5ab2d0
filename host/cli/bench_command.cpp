// `vkray bench SCENE...`: the accelerators against each other on one Vulkan device:
// build and trace time, work per ray, error against run time; writes bench.json, bench.md,
// report.html and images/ into --out, after every scene (marked incomplete until the last, and with
// the failure when a scene fails or the run is interrupted); `--resume` measures only the scenes an
// incomplete report in --out lacks. `--shard I/N` measures a share of the configurations,
// `--merge DIR...` joins the shards' reports into one (docs/cluster.md).
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <tbb/info.h>

#include "accel/accel.h"
#include "bench/bench_interrupt.h"
#include "bench/bench_merge.h"
#include "bench/bench_resume.h"
#include "bench/bench_runner.h"
#include "bench/bench_shard.h"
#include "bench/report.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "core/error.h"
#include "render/device.h"

namespace vkray::cli {
namespace {

struct BenchArgs {
    std::vector<std::string> scenes;
    std::string accels;
    std::string device;
    std::string size;
    std::string view = "scene";
    int repeat = 3;
    std::string out = "vkray-bench";
    std::string threads;
    std::string deltas;
    std::string maxDepths;
    std::string shard;
    std::vector<std::string> merge;
    bool quiet = false;
    bool resume = false;
};

bench::BenchOptions resolveOptions(const BenchArgs& args) {
    bench::BenchOptions o;
    o.scenes = args.scenes;
    if (!args.accels.empty()) o.accels = parseNameList(args.accels, "--accel");
    for (const std::string& a : o.accels) accel::resolveAccel(a);
    if (!args.size.empty()) std::tie(o.width, o.height) = parseSize(args.size);
    o.view = args.view;
    if (args.repeat < 1 || args.repeat > 1000)
        throw Error("--repeat " + std::to_string(args.repeat) + ": expected 1..1000");
    o.repeat = args.repeat;
    if (!args.threads.empty()) {
        // 0 is all cores, as in `vkray render --threads 0`.
        o.threads = parseIntList(args.threads, "--threads", 0, 1024, false);
        for (int& t : o.threads)
            if (t == 0) t = tbb::info::default_concurrency();
    }
    if (!args.deltas.empty()) o.deltas = parseIntList(args.deltas, "--deltas", 1, 1024, true);
    if (args.maxDepths == "none") o.maxDepthSweep = false;
    else if (!args.maxDepths.empty()) o.maxDepths = parseIntList(args.maxDepths, "--maxdepths", 1, 64, false);
    if (!args.shard.empty()) o.shard = bench::parseShard(args.shard);
    return o;
}

std::string joinCommandLine(int argc, const char* const* argv) {
    std::string line;
    for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
    return line;
}

// The progress line: rewritten in place on a terminal; in a log, one line per step (repeats of a
// step are not repeated there).
class ProgressLine {
public:
    explicit ProgressLine(bool quiet) : quiet_(quiet), terminal_(isatty(STDERR_FILENO)) {}
    void operator()(const bench::BenchProgress& p) {
        if (quiet_) return;
        char line[256];
        const std::string repeat = p.repeats > 0 ? (p.repeat == 0 ? " warm-up" : " " + std::to_string(p.repeat) + "/" + std::to_string(p.repeats)) : "";
        std::snprintf(line, sizeof line, "bench: scene %d/%d %s | %s%s | %.1f s", p.scene, p.scenes,
                      p.sceneName.c_str(), p.step.c_str(), repeat.c_str(), p.elapsedSeconds);
        if (terminal_) {
            std::fprintf(stderr, "\r%-100s", line);
        } else if (p.step != lastStep_ || p.sceneName != lastScene_) {
            std::fprintf(stderr, "%s\n", line);
        }
        lastStep_ = p.step;
        lastScene_ = p.sceneName;
    }
    void finish() {
        if (!quiet_ && terminal_) std::fprintf(stderr, "\r%-100s\r", "");
    }

private:
    bool quiet_, terminal_;
    std::string lastStep_, lastScene_;
};

void printSummary(const bench::BenchResults& r, const std::filesystem::path& dir) {
    std::fputs(bench::benchSummary(r).c_str(), stdout);
    std::printf("wrote %s, %s, %s and %s in %.1f s\n", (dir / "bench.json").c_str(), (dir / "bench.md").c_str(),
                (dir / "report.html").c_str(), (dir / "images").c_str(), r.elapsedSeconds);
}

// Printed even with --quiet, as render's warnings are: the figures may mislead without them.
void printWarnings(const bench::BenchResults& r) {
    std::fflush(stdout);  // after the summary, in a terminal that shows both streams
    for (const std::string& w : bench::runWarnings(r)) std::fprintf(stderr, "warning: %s\n", w.c_str());
}

// The output folder must be usable before minutes of measuring.
void prepareOutputDir(const std::filesystem::path& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir))
        throw Error("--out " + dir.string() + ": cannot create the folder" + (ec ? ": " + ec.message() : ""));
    if (access(dir.c_str(), W_OK) != 0) throw Error("--out " + dir.string() + ": the folder is not writable");
}

// Measures, saving the report into `dir` after each scene; a failure leaves the finished scenes
// there, marked incomplete, and a line saying so before the error's.
bench::BenchResults measure(const BenchArgs& args, const bench::BenchOptions& options, const std::string& commandLine,
                            const std::optional<bench::BenchResults>& previous) {
    const std::filesystem::path dir = args.out;
    const bool rayQuery = std::any_of(options.accels.begin(), options.accels.end(), [](const std::string& a) {
        return accel::resolveAccel(a).family == accel::Family::Driver;
    });
    render::Device device(args.device, rayQuery);
    ProgressLine progress(args.quiet);
    bench::BenchContinuation continuation;
    continuation.previous = previous ? &*previous : nullptr;
    continuation.previousFile = (dir / "bench.json").string();
    size_t saved = 0;
    continuation.save = [&](const bench::BenchResults& r) {
        bench::writeBenchReport(r, dir);
        saved = r.scenes.size();
    };
    const bench::StopOnSignals stop;  // SIGINT, SIGTERM: save what is finished, then fail
    bench::BenchResults results;
    try {
        results = bench::runBench(device, options, commandLine,
                                  [&progress](const bench::BenchProgress& p) { progress(p); }, continuation);
    } catch (...) {
        progress.finish();  // the error message gets a line of its own
        if (saved > 0)
            std::fprintf(stderr, "bench: %s holds the %zu finished scene%s, marked incomplete; --resume measures the rest\n",
                         dir.c_str(), saved, saved == 1 ? "" : "s");
        throw;
    }
    progress.finish();
    return results;
}

// `--merge DIR...`: no measuring, no device; the shards' reports become one.
void mergeReports(const BenchArgs& args, const std::string& commandLine) {
    const std::vector<std::filesystem::path> dirs(args.merge.begin(), args.merge.end());
    const bench::BenchResults merged = bench::mergeBenchReports(dirs, commandLine);
    const std::filesystem::path dir = args.out;
    prepareOutputDir(dir);
    bench::writeBenchReport(merged, dir);
    if (!args.quiet) printSummary(merged, dir);
    printWarnings(merged);
}

}  // namespace

void registerBenchCommand(CLI::App& app, int& exitCode, int argc, const char* const* argv) {
    auto* cmd = app.add_subcommand("bench", "Compare accelerators: build and trace time, work per ray, error against run time");
    auto args = std::make_shared<BenchArgs>();
    auto* scenes = cmd->add_option("scenes", args->scenes, "Scene or mesh files (required unless --merge)");
    std::string defaults = "--accel's default:", line;
    for (const std::string& a : bench::BenchOptions{}.accels) {
        if (line.size() + a.size() > 90) defaults += "\n " + line, line.clear();
        line += " " + a;
    }
    cmd->footer(defaults + "\n " + line + "\n`--accel help` lists the names and tuning options.");
    addAccelOption(*cmd, args->accels, "Accelerators, NAME[:OPTION=VALUE...],...; default below")
        ->type_name("LIST");
    cmd->add_option("--device", args->device, "Vulkan device: index or name substring (`vkray devices`)")
        ->type_name("N|NAME");
    cmd->add_option("--size", args->size, "Image size, e.g. 640x480 (default: each scene's)")->type_name("WxH");
    addViewOption(*cmd, args->view);
    cmd->add_option("--repeat", args->repeat, "Timed runs after one warm-up; medians with min-max")
        ->type_name("N")
        ->default_str("3");
    cmd->add_option("--out", args->out, "Folder for bench.json, bench.md, report.html, images/")
        ->type_name("DIR")
        ->default_str(args->out);
    cmd->add_option("--threads", args->threads,
                    "Build thread counts, e.g. 1,2 (0 = all cores; default 1,2,4,...,all)")
        ->type_name("LIST");
    cmd->add_option("--deltas", args->deltas, "AAC delta sweep, or none (default 4,8,12,20,30,50; Mahmuda 2017)")
        ->type_name("LIST");
    cmd->add_option("--maxdepths", args->maxDepths, "maxdepth sweep, e.g. 1,2, or none (default: each below the scene's)")
        ->type_name("LIST");
    cmd->add_option("--shard", args->shard,
                    "Measure shard I (from 0) of N of the configurations (docs/cluster.md)")
        ->type_name("I/N");
    cmd->add_option("--merge", args->merge, "Merge the shards' reports of one run, a folder each, into --out")
        ->type_name("DIR")
        ->expected(1, -1)
        ->excludes(scenes);
    cmd->add_flag("--resume", args->resume,
                  "Continue the run in --out: measure only the scenes it lacks")
        ->excludes("--merge");
    cmd->add_flag("--quiet", args->quiet, "No progress line and no summary: errors and warnings only");
    const std::string commandLine = joinCommandLine(argc, argv);
    cmd->callback([args, commandLine, &exitCode] {
        if (!args->merge.empty()) {
            if (!args->shard.empty()) throw CLI::ValidationError("--merge", "--shard measures, --merge only merges");
            mergeReports(*args, commandLine);
            exitCode = 0;
            return;
        }
        if (args->scenes.empty()) throw CLI::RequiredError("scenes");
        const bench::BenchOptions options = resolveOptions(*args);
        for (const std::string& file : options.scenes)
            if (!std::filesystem::is_regular_file(file)) throw Error(file + ": no such scene file");
        const std::filesystem::path dir = args->out;
        prepareOutputDir(dir);
        std::optional<bench::BenchResults> previous;
        if (args->resume) previous = bench::readResumableReport(dir);
        const bench::BenchResults results = measure(*args, options, commandLine, previous);
        if (previous && previous->complete()) {  // checked by the run; nothing to measure, nothing to rewrite
            if (!args->quiet) std::printf("%s: the run is complete: nothing left to measure\n", (dir / "bench.json").c_str());
            exitCode = 0;
            return;
        }
        bench::writeBenchReport(results, dir);
        if (!args->quiet) printSummary(results, dir);
        printWarnings(results);
        exitCode = 0;
    });
}

}  // namespace vkray::cli
