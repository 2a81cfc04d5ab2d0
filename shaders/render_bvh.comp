// Render kernel with the `bvh` accelerator: AAC (or binned-SAH) BVH; closest hits by the
// near-child-first stack walk, shadow rays by the stackless walk (parent links).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#include "include/bvh_traversal.glsl"
#include "include/render_main.glsl"
