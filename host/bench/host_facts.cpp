#include "bench/host_facts.h"

#include <cstdlib>
#include <ctime>

#include <unistd.h>

namespace vkray::bench {

std::string isoTimeUtc() {
    const std::time_t now = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return text;
}

std::optional<double> loadAverage() {
    double load[1];
    if (getloadavg(load, 1) != 1) return std::nullopt;
    return load[0];
}

std::string hostName() {
    char name[256] = {};
    if (gethostname(name, sizeof name - 1) != 0) return "unknown";
    return name;
}

}  // namespace vkray::bench
