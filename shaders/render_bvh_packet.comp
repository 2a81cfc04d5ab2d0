// Render kernel with `bvh-packet`: the AAC BVH of `bvh`, its closest hits walked by the subgroup's
// rays as one packet (bvh_packet.glsl). Shadow rays take the single-ray stackless walk, as in every
// BVH kernel: a packet any-hit walk, whose lanes drop out as their rays are blocked, gained nothing
// measurable over it on lavapipe (docs/performance.md, "Packet traversal"). The resumable variant
// walks closest hits stackless too: it saves an interrupted walk as a node and a slot per pixel
// (bvh_stackless.glsl), which a packet, whose lanes stop at different points of their pixels, has
// no single one of; and the tiles it takes up are the few whose rays ran out of lavapipe's loop
// budget.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require

#include "include/bvh_packet.glsl"
#include "include/bvh_stackless.glsl"

Hit traceClosest(vec3 origin, vec3 dir, float tmax) {
    if (RESUMABLE) return bvhStacklessTrace(origin, dir, tmax, false);
    return bvhPacketTrace(origin, dir, tmax);
}
bool traceAny(vec3 origin, vec3 dir, float tmax) { return bvhStacklessTrace(origin, dir, tmax, true).triangle >= 0; }

#include "include/render_main.glsl"
