// Render kernel with `kd-packet`: kd-stack's SAH kd-tree, its camera rays walked by the subgroup's
// rays as packets (kd_packet.glsl; traceCamera, accelerator.glsl). Reflection, refraction and
// shadow rays, and the resumable variant, take kd-stack's walk, one ray a lane, as bvh-packet's
// take the single-ray walks of theirs (render_bvh_packet.comp): diverging rays cost more in packets,
// and the resumable variant saves no packet state.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require

#define VKRAY_OWN_CAMERA_TRACE
#include "include/kd_stack.glsl"
#include "include/kd_packet.glsl"

Hit traceCamera(vec3 origin, vec3 dir, float tmax) { return kdPacketTrace(origin, dir, tmax); }

#include "include/render_main.glsl"
