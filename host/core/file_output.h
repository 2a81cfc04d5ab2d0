// Writing a whole file, checked: the one place vkray's outputs (images, AOVs, bench reports) go to
// disk, so every output fails the same way. Errors name the file (FileLoc) and the system's reason.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string_view>

namespace vkray {

// Writes `size` bytes to `path`, replacing it. Throws vkray::Error "PATH: cannot open for writing:
// REASON" or "PATH: write failed: REASON" (a full disk shows at fwrite or at fclose); on a failed
// write the partial file is removed, so no half-written output is left behind.
void writeFileBytes(const std::filesystem::path& path, const void* bytes, size_t size);
void writeFileText(const std::filesystem::path& path, std::string_view text);

}  // namespace vkray
