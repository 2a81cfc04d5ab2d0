#include "core/suggest.h"

#include <algorithm>
#include <cctype>
#include <vector>

namespace vkray {

size_t editDistance(std::string_view a, std::string_view b) {
    const auto same = [](char x, char y) {
        return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
    };
    // d[i][j]: distance between a's first i characters and b's first j, three rows kept.
    std::vector<size_t> before(b.size() + 1), previous(b.size() + 1), current(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) previous[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t substitute = previous[j - 1] + (same(a[i - 1], b[j - 1]) ? 0 : 1);
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitute});
            if (i > 1 && j > 1 && same(a[i - 1], b[j - 2]) && same(a[i - 2], b[j - 1]))
                current[j] = std::min(current[j], before[j - 2] + 1);  // two neighbours swapped
        }
        std::swap(before, previous);
        std::swap(previous, current);
    }
    return previous[b.size()];
}

std::optional<std::string> closestName(std::string_view typed, std::span<const std::string_view> known) {
    const size_t limit = std::min<size_t>(2, (typed.size() + 2) / 3);
    std::optional<std::string> best;
    size_t bestDistance = limit + 1;
    for (std::string_view name : known) {
        const size_t d = editDistance(typed, name);
        if (d < bestDistance) {
            bestDistance = d;
            best = std::string(name);
        }
    }
    return best;
}

}  // namespace vkray
