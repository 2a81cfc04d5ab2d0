// The summary every benchmark prints for repeated measurements (docs/performance.md,
// "Method"): the median with the spread as min-max.
#pragma once

#include <algorithm>
#include <vector>

namespace vkray::bench {

struct Spread {
    double median = 0.0, min = 0.0, max = 0.0;
};

// Of at least one value.
inline Spread spreadOf(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return {n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]), v.front(), v.back()};
}

}  // namespace vkray::bench
