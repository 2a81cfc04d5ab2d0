// What every traversal reports besides its hit: whether a loop was cut short by the driver, rays
// ended by an iteration cap, and (in the statistics variant only) the work done.
//
// llvmpipe (lavapipe) ends every loop of an invocation once its loops together ran 65535
// iterations (Mesa gallivm LP_MAX_TGSI_LOOP_ITERATIONS). A traversal loop that ends before its own
// exit condition and before its cap sets gLoopCutShort, so such a pixel is flagged, never silently
// wrong. A loop that reaches its own iteration cap (a runaway ray: lavapipe has no watchdog)
// counts the ray in gCappedRays instead.
#ifndef VKRAY_TRACE_STATUS_GLSL
#define VKRAY_TRACE_STATUS_GLSL

#include "bindings.glsl"

layout(constant_id = VKRAY_SPEC_COUNT_TRAVERSAL) const bool COUNT_TRAVERSAL = false;

bool gLoopCutShort = false;
uint gCappedRays = 0;
uint gShadowRays = 0;
uint gNodesVisited = 0;
uint gLeavesVisited = 0;
uint gTrianglesTested = 0;
uint gRestarts = 0;

// The counters compile to nothing unless the host specialises COUNT_TRAVERSAL to true.
void countNode() { if (COUNT_TRAVERSAL) ++gNodesVisited; }
void countLeaf() { if (COUNT_TRAVERSAL) ++gLeavesVisited; }
void countTriangles(uint n) { if (COUNT_TRAVERSAL) gTrianglesTested += n; }
void countRestart() { if (COUNT_TRAVERSAL) ++gRestarts; }

#endif
