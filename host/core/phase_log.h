// Times the phases of a build (for --stats) and reports them to a progress callback as they start.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/timing.h"

namespace vkray {

// Progress of a long build, for a progress line: what is being done and the fraction of the whole
// build done (0..1). Called from one thread at a time.
using BuildProgress = std::function<void(const std::string& phase, double fraction)>;

class PhaseLog {
public:
    explicit PhaseLog(BuildProgress progress = {}) : progress_(std::move(progress)) {}

    // Runs f as phase `name` (a stats key stem such as "sort"); `endFraction` is the share of the
    // whole build done once it returns, an estimate for the progress line only.
    template <class F>
    decltype(auto) run(const std::string& name, double endFraction, F&& f) {
        if (progress_) progress_(name, fraction_);
        struct Record {  // records the phase however f returns
            PhaseLog& log;
            const std::string& name;
            Clock::time_point start;
            double endFraction;
            ~Record() {
                log.phases_.emplace_back(name, msSince(start));
                log.fraction_ = endFraction;
            }
        } record{*this, name, Clock::now(), endFraction};
        return f();
    }

    void finish() {
        if (progress_) progress_("done", 1.0);
    }

    // (name, milliseconds) in the order run.
    const std::vector<std::pair<std::string, double>>& phases() const { return phases_; }

private:
    BuildProgress progress_;
    double fraction_ = 0.0;
    std::vector<std::pair<std::string, double>> phases_;
};

}  // namespace vkray
