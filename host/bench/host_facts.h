// What a bench report records of the machine and the moment it ran on, so that figures from
// different runs can be told apart (bench_results.h: startedAt, node, the load averages).
#pragma once

#include <optional>
#include <string>

namespace vkray::bench {

// Now, as "2026-01-31T12:00:00Z".
std::string isoTimeUtc();

// The machine's 1-minute load average, for the warning about other work competing with the run;
// none where the system does not tell it.
std::optional<double> loadAverage();

// The machine's name, "unknown" where it has none.
std::string hostName();

}  // namespace vkray::bench
