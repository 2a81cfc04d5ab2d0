// bench_run_state.h.
#include "bench/bench_run_state.h"

#include <algorithm>
#include <exception>
#include <thread>

#include "bench/bench_resume.h"
#include "bench/bench_shard.h"
#include "bench/host_facts.h"
#include "core/error.h"
#include "vkray_revision.h"  // generated at build time by scripts/revision.cmake

namespace vkray::bench {

BenchResults runHeader(const BenchOptions& options, const std::string& commandLine) {
    BenchResults results;
    results.vkrayVersion = VKRAY_VERSION;
    results.revision = VKRAY_REVISION;
    results.commandLine = commandLine;
    results.startedAt = isoTimeUtc();
    results.hardwareThreads = int(std::thread::hardware_concurrency());
    results.loadAverageStart = loadAverage();
    results.repeat = options.repeat;
    results.node = hostName();
    results.settings = benchSettings(options);
    results.shard = options.shard;
    const std::vector<Configuration> list = configurationList(results.settings);
    results.configurationCount = list.size();
    results.configurationHash = configurationHash(list);
    return results;
}

void setDevice(BenchResults& results, const gpu::VulkanContext& ctx) {
    results.device = ctx.info().name;
    results.driver = ctx.info().driver;
    results.deviceType = ctx.info().type;
    results.vulkanApi = ctx.info().apiVersion;
}

void continueFrom(const BenchResults& previous, const std::string& file, BenchResults& results) {
    checkResumableSettings(previous, results, file);
    results.scenes = previous.scenes;
    results.startedAt = previous.startedAt;
}

void stampResults(BenchResults& results, Clock::time_point start, double before, std::string failure) {
    std::stable_sort(results.scenes.begin(), results.scenes.end(),
                     [](const SceneResult& a, const SceneResult& b) { return a.index < b.index; });
    results.loadAverageEnd = loadAverage();
    results.elapsedSeconds = before + msSince(start) / 1000.0;
    results.failure = std::move(failure);
}

[[noreturn]] void saveAndRethrow(BenchResults& results, Clock::time_point start, double before,
                                 const BenchSaveFn& save) {
    const std::exception_ptr error = std::current_exception();
    std::string what = "an unknown error";
    try {
        throw;
    } catch (const std::exception& e) {
        what = e.what();
    } catch (...) {
    }
    stampResults(results, start, before, what);
    if (save) {
        try {
            save(results);
        } catch (const std::exception& e) {
            throw Error(what + " (and the finished scenes could not be saved: " + e.what() + ")");
        }
    }
    std::rethrow_exception(error);
}

}  // namespace vkray::bench
