// Writing files, checked: the one place vkray's outputs (images, AOVs, bench reports, structure
// files) go to disk, so every output fails the same way. Errors name the file (FileLoc) and the
// system's reason.
#pragma once

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string_view>

namespace vkray {

// Writes `size` bytes to `path`, replacing it. Throws vkray::Error "PATH: cannot open for writing:
// REASON" or "PATH: write failed: REASON" (a full disk shows at fwrite or at fclose); on a failed
// write the partial file is removed, so no half-written output is left behind.
void writeFileBytes(const std::filesystem::path& path, const void* bytes, size_t size);
void writeFileText(const std::filesystem::path& path, std::string_view text);

// A file too big to hold in memory at once, written piece by piece: to PATH.tmp, renamed to PATH by
// commit(), and removed if it is destroyed before (a failure, an exception), so an interrupted write
// never leaves a partial file under the name. Errors: "PATH: cannot open PATH.tmp for writing:
// REASON", "PATH: cannot write PATH.tmp: REASON", "PATH: cannot rename PATH.tmp to it: REASON".
class StreamedFileWriter {
public:
    explicit StreamedFileWriter(const std::filesystem::path& path);
    ~StreamedFileWriter();
    StreamedFileWriter(const StreamedFileWriter&) = delete;
    StreamedFileWriter& operator=(const StreamedFileWriter&) = delete;

    void write(const void* data, size_t size);
    void commit();

private:
    std::filesystem::path path_, temp_;
    std::FILE* file_ = nullptr;
    bool committed_ = false;
};

}  // namespace vkray
