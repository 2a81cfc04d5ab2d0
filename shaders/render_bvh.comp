// Render kernel with the `bvh` accelerator: AAC (or binned-SAH) BVH, near-child-first stack traversal.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require

#include "include/bvh_traversal.glsl"
#include "include/render_main.glsl"
