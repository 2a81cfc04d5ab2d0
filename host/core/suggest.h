// "Did you mean": the known name closest to a mistyped one, by edit distance.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace vkray {

// Edits (insert, delete, substitute a character, or swap two neighbours) that turn a into b,
// ignoring ASCII case (the optimal-string-alignment distance).
size_t editDistance(std::string_view a, std::string_view b);

// The name of `known` closest to `typed` when it is close enough to be what was meant: at most 2
// edits, and at most a third of the typed word's length (rounded up), so `sphre` finds `sphere` and
// `foo` finds nothing. Ties go to the first in `known`.
std::optional<std::string> closestName(std::string_view typed, std::span<const std::string_view> known);
inline std::optional<std::string> closestName(std::string_view typed, const std::vector<std::string>& known) {
    const std::vector<std::string_view> views(known.begin(), known.end());
    return closestName(typed, views);
}

}  // namespace vkray
