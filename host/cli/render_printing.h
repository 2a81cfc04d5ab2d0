// What `vkray render` prints: the report of each scene (render::RenderReport) for people (a few
// lines, more with --stats) or as JSON for scripts (--json; the keys are stable), the values of
// --pixel, and the progress line on stderr.
#pragma once

#include <string>

#include "frame/frame.h"
#include "render/render_report.h"
#include "render/render_request.h"

namespace vkray::cli {

using render::RenderReport;

// The whole report as one JSON object (--json).
std::string reportJson(const RenderReport& report);

// The summary on stdout; with `stats`, the scene, the build, the kernel and the timings too.
void printReport(const RenderReport& report, bool stats);

// --pixel: the one pixel's values on stdout.
void printPixel(const Frame& frame, const RenderReport& report);

// The progress line on stderr, rewritten in place (for a terminal only: logs stay clean).
render::Progress progressLine();

}  // namespace vkray::cli
