// vkray's one error type: every failure the user can cause (bad input, a missing device, a Vulkan
// call that fails) is thrown as vkray::Error and printed as one line by main(), which exits non-zero.
// A location (file:line[:col]) is attached whenever the cause sits in an input file, after the
// pbrt-v4 FileLoc convention: "error: scene.scene:12: expected 3 numbers after 'vertex'".
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

namespace vkray {

struct FileLoc {
    std::string file;  // as the user named it (or as resolved relative to the including file)
    int line = 0;      // 1-based; 0 = the file as a whole
    int col = 0;       // 1-based; 0 = unknown

    std::string str() const;  // "file", "file:line" or "file:line:col"
};

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
    Error(FileLoc loc, const std::string& what);

    bool hasLocation() const { return hasLoc_; }
    const FileLoc& location() const { return loc_; }

private:
    FileLoc loc_;
    bool hasLoc_ = false;
};

// The error of a file as a whole, "PATH: what": an image, a structure file, a report that cannot be
// written.
inline Error fileError(const std::filesystem::path& path, const std::string& what) {
    return Error(FileLoc{path.string()}, what);
}

}  // namespace vkray
