// The report's pictures (see report_images.h): names, the heatmap scale, PNG and base64 encoding.
#include "bench/report_images.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <utility>

#include "bench/colormap.h"
#include "image/image_io.h"

namespace vkray::bench {
namespace {

// Letters, digits, '.', '-' and '_' survive; anything else (spaces, slashes) becomes '_', so a
// name is a plain file name on every system.
std::string safeName(const std::string& s) {
    std::string out;
    for (unsigned char c : s) out += std::isalnum(c) || c == '.' || c == '-' || c == '_' ? char(c) : '_';
    return out.empty() ? "scene" : out;
}

// Hands out names unique in the report: a second "bunny_bvh.png" becomes "bunny_bvh-2.png".
class FileNames {
public:
    std::string claim(const std::string& stem) {
        std::string name = stem + ".png";
        for (int n = 2; !used_.insert(name).second; ++n) name = stem + "-" + std::to_string(n) + ".png";
        return name;
    }

private:
    std::set<std::string> used_;
};

bool isDrawable(const Image& im) {
    return im.width > 0 && im.height > 0 && (im.channels == 1 || im.channels == 3) &&
           im.data.size() == im.pixelCount() * size_t(im.channels);
}

// The size of an accelerator's per-pixel counts: its render's size, else the scene's; none when
// the counts fit neither (a runner that recorded no counters).
bool heatmapSize(const SceneResult& s, const AccelResult& a, HeatmapRays rays, int& w, int& h) {
    const std::vector<uint32_t>& counts = heatmapCounts(a, rays);
    if (counts.empty()) return false;
    for (auto [cw, ch] : {std::pair{a.image.width, a.image.height}, std::pair{s.width, s.height}})
        if (cw > 0 && ch > 0 && counts.size() == size_t(cw) * size_t(ch)) {
            w = cw;
            h = ch;
            return true;
        }
    return false;
}

// Renders (the reference's and each accelerator's) are radiance: sRGB-encoded like `vkray render`'s
// PNGs. Difference images and heatmaps already hold display colours: stored as they are.
ReportImage encoded(size_t scene, const std::string& accel, ImageRole role, std::string fileName, const Image& im) {
    const bool radiance = role == ImageRole::Reference || role == ImageRole::Render;
    return ReportImage{scene, accel, role, std::move(fileName), im.width, im.height,
                       encodePng(im, radiance ? Encoding{} : Encoding::linear())};
}

}  // namespace

uint32_t percentile(std::vector<uint32_t> values, double p) {
    if (values.empty()) return 0;
    const double rank = std::ceil(std::clamp(p, 0.0, 100.0) / 100.0 * double(values.size()));
    const size_t k = std::min(values.size() - 1, size_t(std::max(1.0, rank)) - 1);
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.end());
    return values[k];
}

const std::vector<uint32_t>& heatmapCounts(const AccelResult& a, HeatmapRays rays) {
    return rays == HeatmapRays::Camera ? a.primaryNodesPerPixel : a.nodesPerPixel;
}

HeatmapScale heatmapScale(const SceneResult& s, HeatmapRays rays) {
    std::vector<uint32_t> all;
    for (const AccelResult& a : s.accels) {
        int w = 0, h = 0;
        const std::vector<uint32_t>& counts = heatmapCounts(a, rays);
        if (heatmapSize(s, a, rays, w, h)) all.insert(all.end(), counts.begin(), counts.end());
    }
    HeatmapScale scale;
    if (all.empty()) return scale;
    scale.any = true;
    scale.largest = *std::max_element(all.begin(), all.end());
    // Mostly-empty pictures (a sky) can have a 99th percentile of 0: fall back to the largest.
    const uint32_t p99 = percentile(std::move(all), 99.0);
    scale.max = double(std::max<uint32_t>(1, p99 > 0 ? p99 : scale.largest));
    return scale;
}

std::vector<ReportImage> reportImages(const BenchResults& results) {
    std::vector<ReportImage> out;
    FileNames names;
    for (size_t si = 0; si < results.scenes.size(); ++si) {
        const SceneResult& s = results.scenes[si];
        const std::string stem = safeName(s.name);
        if (isDrawable(s.reference))
            out.push_back(encoded(si, "", ImageRole::Reference, names.claim(stem + "_reference"), s.reference));
        const HeatmapScale scale = heatmapScale(s, HeatmapRays::All);
        const HeatmapScale cameraScale = heatmapScale(s, HeatmapRays::Camera);
        for (const AccelResult& a : s.accels) {
            const std::string accelStem = stem + "_" + safeName(a.accel);
            if (isDrawable(a.image))
                out.push_back(encoded(si, a.accel, ImageRole::Render, names.claim(accelStem), a.image));
            if (isDrawable(a.diff))
                out.push_back(encoded(si, a.accel, ImageRole::Difference, names.claim(accelStem + "_diff"), a.diff));
            int w = 0, h = 0;
            if (heatmapSize(s, a, HeatmapRays::All, w, h))
                out.push_back(encoded(si, a.accel, ImageRole::Heatmap, names.claim(accelStem + "_nodes"),
                                      heatmapImage(a.nodesPerPixel, w, h, scale.max)));
            if (heatmapSize(s, a, HeatmapRays::Camera, w, h))
                out.push_back(encoded(si, a.accel, ImageRole::PrimaryHeatmap, names.claim(accelStem + "_primary_nodes"),
                                      heatmapImage(a.primaryNodesPerPixel, w, h, cameraScale.max)));
        }
    }
    return out;
}

std::string base64(const std::vector<unsigned char>& bytes) {
    static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const size_t n = std::min<size_t>(3, bytes.size() - i);
        uint32_t group = uint32_t(bytes[i]) << 16;
        if (n > 1) group |= uint32_t(bytes[i + 1]) << 8;
        if (n > 2) group |= uint32_t(bytes[i + 2]);
        for (size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

}  // namespace vkray::bench
