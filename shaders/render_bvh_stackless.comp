// Render kernel with `bvh-stackless`: the AAC BVH of `bvh`, walked with parent links instead of a
// stack for closest hits too.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#include "include/bvh_stackless.glsl"

Hit traceClosest(vec3 origin, vec3 dir, float tmax) { return bvhStacklessTrace(origin, dir, tmax, false); }
bool traceAny(vec3 origin, vec3 dir, float tmax) { return bvhStacklessTrace(origin, dir, tmax, true).triangle >= 0; }

#include "include/render_main.glsl"
