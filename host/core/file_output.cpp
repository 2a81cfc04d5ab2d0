#include "core/file_output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>

#include "core/error.h"

namespace vkray {

void writeFileBytes(const std::filesystem::path& path, const void* bytes, size_t size) {
    const auto fail = [&](const std::string& what, int err) {
        return Error(FileLoc{path.string()}, what + std::strerror(err != 0 ? err : EIO));
    };
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw fail("cannot open for writing: ", errno);
    const size_t written = std::fwrite(bytes, 1, size, f);
    int err = written == size ? 0 : errno;
    if (std::fclose(f) != 0 && err == 0) err = errno;
    if (written != size || err != 0) {
        std::error_code ignored;
        std::filesystem::remove(path, ignored);
        throw fail("write failed: ", err);
    }
}

void writeFileText(const std::filesystem::path& path, std::string_view text) {
    writeFileBytes(path, text.data(), text.size());
}

}  // namespace vkray
