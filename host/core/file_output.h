// Writing files, checked and atomic: the one place vkray's outputs (images, AOVs, generated scenes,
// bench reports, structure files) go to disk, so every output fails the same way and none is ever
// left half-written. Errors name the file (FileLoc) and the system's reason, on one line:
// "PATH: cannot open for writing: REASON" or "PATH: write failed: REASON".
//
// A file is written to a temporary of a unique name in its own directory (".NAME.vkray-XXXXXX"),
// flushed to the disk, and renamed over PATH only when complete. Until then PATH is untouched: a
// failure (a full disk, a read-only directory) or an exception leaves the previous file
// byte-identical and removes the temporary, and so does SIGINT/SIGTERM/SIGHUP (core/temp_files.h).
// - The new file keeps an existing file's mode bits (a new one gets 0666 less the umask, as fopen).
// - A symbolic link is written through: the file it points at is replaced, the link stays.
// - A file with other hard links is replaced under the name written only: its other names keep the
//   previous content (as after any save by rename).
// - A target that exists and is not a regular file (/dev/null, /dev/stdout, a FIFO) is written
//   directly, without a temporary, and never removed.
// - An existing file the user may not write (mode 0444) is refused, as fopen would refuse it,
//   though the directory would allow the rename.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace vkray {

// Writes `size` bytes to `path`, replacing it.
void writeFileBytes(const std::filesystem::path& path, const void* bytes, size_t size);
void writeFileText(const std::filesystem::path& path, std::string_view text);

// A file written piece by piece (too big to hold in memory at once, or produced as it goes):
// replaces PATH at commit(); destroyed before that (a failure, an exception), PATH is untouched and
// the temporary removed. Constructing one is the sure test of whether PATH can be written (the
// directory's permissions, file system and quotas): it creates the temporary file.
class StreamedFileWriter {
public:
    explicit StreamedFileWriter(const std::filesystem::path& path);
    ~StreamedFileWriter();
    StreamedFileWriter(const StreamedFileWriter&) = delete;
    StreamedFileWriter& operator=(const StreamedFileWriter&) = delete;

    void write(const void* data, size_t size);
    void commit();

    // The temporary file being written, absolute; empty when the target is written directly (a
    // device, a FIFO).
    const std::filesystem::path& temporaryPath() const { return temp_; }

private:
    void openTemporary(unsigned mode, bool exists, unsigned owner, unsigned group);
    void openDirect();
    void discard() noexcept;  // closes, and removes the temporary unless committed

    std::filesystem::path path_;    // as the caller named it, for errors
    std::filesystem::path target_;  // absolute, symbolic links followed: what is replaced (empty: a device)
    std::filesystem::path temp_;
    int fd_ = -1;
    int slot_ = -1;  // core/temp_files.h
    bool committed_ = false;
};

// The prefix and infix of the temporary files of `target` (".NAME.vkray-"), for tests and tools that
// look for leftovers.
std::string temporaryNamePrefix(const std::filesystem::path& target);

}  // namespace vkray
