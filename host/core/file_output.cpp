#include "core/file_output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>

#include "core/error.h"

namespace vkray {
namespace {

// "PATH: WHAT: REASON", the reason from errno (EIO when the library left none).
Error systemError(const std::filesystem::path& path, const std::string& what, int err) {
    return Error(FileLoc{path.string()}, what + ": " + std::strerror(err != 0 ? err : EIO));
}

}  // namespace

void writeFileBytes(const std::filesystem::path& path, const void* bytes, size_t size) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw systemError(path, "cannot open for writing", errno);
    const size_t written = std::fwrite(bytes, 1, size, f);
    int err = written == size ? 0 : errno;
    if (std::fclose(f) != 0 && err == 0) err = errno;
    if (written != size || err != 0) {
        std::error_code ignored;
        std::filesystem::remove(path, ignored);
        throw systemError(path, "write failed", err);
    }
}

void writeFileText(const std::filesystem::path& path, std::string_view text) {
    writeFileBytes(path, text.data(), text.size());
}

StreamedFileWriter::StreamedFileWriter(const std::filesystem::path& path)
    : path_(path), temp_(path.string() + ".tmp") {
    file_ = std::fopen(temp_.c_str(), "wb");
    if (!file_) throw systemError(path_, "cannot open " + temp_.string() + " for writing", errno);
}

StreamedFileWriter::~StreamedFileWriter() {
    if (file_) std::fclose(file_);
    if (!committed_) {
        std::error_code ignored;
        std::filesystem::remove(temp_, ignored);
    }
}

void StreamedFileWriter::write(const void* data, size_t size) {
    if (size > 0 && std::fwrite(data, 1, size, file_) != size)
        throw systemError(path_, "cannot write " + temp_.string(), errno);
}

void StreamedFileWriter::commit() {
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if (closed != 0) throw systemError(path_, "cannot write " + temp_.string(), errno);
    std::error_code ec;
    std::filesystem::rename(temp_, path_, ec);
    if (ec) throw Error(FileLoc{path_.string()}, "cannot rename " + temp_.string() + " to it: " + ec.message());
    committed_ = true;
}

}  // namespace vkray
