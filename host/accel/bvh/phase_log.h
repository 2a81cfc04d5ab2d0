// Times the phases of a build (for --stats) and reports them to a progress callback as they start.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vkray::bvh {

class PhaseLog {
public:
    // progress(phase, fraction of the whole build done when the phase starts); may be empty.
    using Progress = std::function<void(const std::string&, double)>;

    explicit PhaseLog(Progress progress = {}) : progress_(std::move(progress)) {}

    // Runs f as phase `name` (a stats key stem such as "sort"); `endFraction` is the share of the
    // whole build done once it returns, an estimate for the progress line only.
    template <class F>
    decltype(auto) run(const std::string& name, double endFraction, F&& f) {
        if (progress_) progress_(name, fraction_);
        const auto start = std::chrono::steady_clock::now();
        struct Record {  // records the phase however f returns
            PhaseLog& log;
            const std::string& name;
            std::chrono::steady_clock::time_point start;
            double endFraction;
            ~Record() {
                const std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - start;
                log.phases_.emplace_back(name, ms.count());
                log.fraction_ = endFraction;
            }
        } record{*this, name, start, endFraction};
        return f();
    }

    void finish() {
        if (progress_) progress_("done", 1.0);
    }

    // (name, milliseconds) in the order run.
    const std::vector<std::pair<std::string, double>>& phases() const { return phases_; }

private:
    Progress progress_;
    double fraction_ = 0.0;
    std::vector<std::pair<std::string, double>> phases_;
};

}  // namespace vkray::bvh
