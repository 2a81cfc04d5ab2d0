#include "core/error.h"

// Out of line on purpose: GCC 12 inlines these concatenations and then emits a false -Wrestrict
// warning (GCC bug 105329) in every file that throws an Error with a location.
namespace vkray {

std::string FileLoc::str() const {
    std::string s = file;
    if (line > 0) s.append(":").append(std::to_string(line));
    if (line > 0 && col > 0) s.append(":").append(std::to_string(col));
    return s;
}

Error::Error(FileLoc loc, const std::string& what)
    : std::runtime_error(loc.str() + ": " + what), loc_(std::move(loc)), hasLoc_(true) {}

}  // namespace vkray
