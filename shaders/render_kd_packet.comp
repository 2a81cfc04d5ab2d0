// Render kernel with `kd-packet`: kd-stack's SAH kd-tree, its closest hits walked by the subgroup's
// rays as packets (kd_packet.glsl). Shadow rays and the resumable variant take kd-stack's walk, one
// ray a lane, as bvh-packet's take the single-ray walk of theirs (render_bvh_packet.comp): the
// resumable variant saves no packet state, and the tiles it takes up are the few whose rays ran out
// of lavapipe's loop budget.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require

#define VKRAY_KD_OWN_CLOSEST
#include "include/kd_stack.glsl"
#include "include/kd_packet.glsl"

Hit traceClosest(vec3 origin, vec3 dir, float tmax) {
    if (RESUMABLE) return kdTrace(origin, dir, tmax, false);
    return kdPacketTrace(origin, dir, tmax);
}

#include "include/render_main.glsl"
