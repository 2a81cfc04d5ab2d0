// writeBenchReport (report.h): the output folder of `vkray bench`, every file checked as written.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>

#include "bench/report.h"
#include "bench/report_images.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace vkray::bench {
namespace {

Error fileError(const fs::path& path, const std::string& what) { return Error(FileLoc{path.string()}, what); }

void makeDirectory(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    // create_directories reports no error when the path exists as a file: check what is there.
    if (ec || !fs::is_directory(dir))
        throw fileError(dir, "cannot create the directory" + (ec ? ": " + ec.message() : ": a file of that name exists"));
}

// Writes all bytes or throws, closing the file either way.
void writeFile(const fs::path& path, const void* bytes, size_t size) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw fileError(path, std::string("cannot open for writing: ") + std::strerror(errno));
    const size_t written = std::fwrite(bytes, 1, size, f);
    int err = written == size ? 0 : errno;
    if (std::fclose(f) != 0 && err == 0) err = errno;
    if (written != size || err != 0) throw fileError(path, std::string("write failed: ") + std::strerror(err ? err : EIO));
}

void writeText(const fs::path& path, const std::string& text) { writeFile(path, text.data(), text.size()); }

}  // namespace

void writeBenchReport(const BenchResults& results, const fs::path& dir) {
    // Everything is produced before the first file is written, so a failure to encode cannot leave
    // a half-written report behind.
    const std::vector<ReportImage> images = reportImages(results);
    const std::string json = benchJson(results);
    const std::string markdown = benchMarkdown(results);
    const std::string html = benchHtml(results, images);

    makeDirectory(dir);
    makeDirectory(dir / "images");
    writeText(dir / "bench.json", json);
    writeText(dir / "bench.md", markdown);
    writeText(dir / "report.html", html);
    for (const ReportImage& im : images) writeFile(dir / "images" / im.fileName, im.png.data(), im.png.size());
}

}  // namespace vkray::bench
