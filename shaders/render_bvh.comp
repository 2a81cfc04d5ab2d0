// Render kernel with the `bvh` accelerator: AAC (or binned-SAH) BVH; closest hits by the
// near-child-first stack walk, shadow rays by the stackless walk (parent links).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require

#include "include/bvh_stackless.glsl"
#include "include/bvh_traversal.glsl"

Hit traceClosest(vec3 origin, vec3 dir, float tmax) { return bvhTrace(origin, dir, tmax); }
bool traceAny(vec3 origin, vec3 dir, float tmax) { return bvhStacklessTrace(origin, dir, tmax, true).triangle >= 0; }

#include "include/render_main.glsl"
