// writeBenchReport (report.h): the output folder of `vkray bench`, every file checked as written.
#include <filesystem>
#include <string>
#include <system_error>

#include "bench/bench_json.h"
#include "bench/report.h"
#include "bench/report_images.h"
#include "core/error.h"
#include "core/file_output.h"
#include "image/image_io.h"

namespace fs = std::filesystem;

namespace vkray::bench {
namespace {

void makeDirectory(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    // create_directories reports no error when the path exists as a file: check what is there.
    if (ec || !fs::is_directory(dir))
        throw fileError(dir, "cannot create the directory" + (ec ? ": " + ec.message() : ": a file of that name exists"));
}

// What each picture is drawn from, as a PFM beside it (bench_json.h, pixelsFileName).
void writePixels(const BenchResults& results, const std::vector<ReportImage>& images, const fs::path& dir) {
    for (const ReportImage& im : images) {
        const SceneResult& scene = results.scenes[im.scene];
        const fs::path path = dir / "images" / pixelsFileName(im.fileName);
        if (im.role == ImageRole::Reference) writeImage(path, scene.reference);
        for (const AccelResult& a : scene.accels) {
            if (a.accel != im.accel) continue;
            if (im.role == ImageRole::Render) writeImage(path, a.image);
            if (im.role == ImageRole::Difference) writeImage(path, a.diff);
            if (im.role == ImageRole::Heatmap || im.role == ImageRole::PrimaryHeatmap) {
                const std::vector<uint32_t>& n =
                    heatmapCounts(a, im.role == ImageRole::Heatmap ? HeatmapRays::All : HeatmapRays::Camera);
                const std::vector<float> counts(n.begin(), n.end());
                writePfm(path, im.width, im.height, 1, counts.data());
            }
        }
    }
}

// The pixels an incomplete report kept for `--resume` (keepsPixels): a report that keeps none
// leaves none of an earlier one behind.
void removePixels(const fs::path& images) {
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(images, ec))
        if (e.path().extension() == ".pfm") fs::remove(e.path(), ec);
}

}  // namespace

void writeBenchReport(const BenchResults& results, const fs::path& dir) {
    // Everything is produced before the first file is written, so a failure to encode cannot leave
    // a half-written report behind.
    const std::vector<ReportImage> images = reportImages(results);
    const std::string json = benchJson(results, images);
    const std::string markdown = benchMarkdown(results);
    const std::string html = benchHtml(results, images);

    makeDirectory(dir);
    makeDirectory(dir / "images");
    writeFileText(dir / "bench.json", json);
    writeFileText(dir / "bench.md", markdown);
    writeFileText(dir / "report.html", html);
    for (const ReportImage& im : images) writeFileBytes(dir / "images" / im.fileName, im.png.data(), im.png.size());
    if (keepsPixels(results)) writePixels(results, images, dir);
    else removePixels(dir / "images");
}

}  // namespace vkray::bench
