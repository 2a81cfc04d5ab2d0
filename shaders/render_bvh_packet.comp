// Render kernel with `bvh-packet`: the AAC BVH of `bvh`, its camera rays walked by the subgroup's
// rays as one packet (bvh_packet.glsl; traceCamera, accelerator.glsl). Camera rays travel together
// by construction; reflection and refraction rays diverge, and in packets they cost more than each
// walking alone (docs/performance.md, "Packet traversal"), so they take `bvh`'s stack walk, and
// shadow rays its stackless walk, as in every BVH kernel: a packet any-hit walk, whose lanes drop
// out as their rays are blocked, gained nothing measurable over it on lavapipe. The resumable
// variant walks closest hits stackless: it saves an interrupted walk as a node and a slot per pixel
// (bvh_stackless.glsl), which a packet, whose lanes stop at different points of their pixels, has
// no single one of; and the tiles it takes up are the few whose rays ran out of lavapipe's loop
// budget.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require

#define VKRAY_OWN_CAMERA_TRACE
#include "include/bvh_packet.glsl"
#include "include/bvh_traversal.glsl"

Hit traceCamera(vec3 origin, vec3 dir, float tmax) { return bvhPacketTrace(origin, dir, tmax); }

#include "include/render_main.glsl"
