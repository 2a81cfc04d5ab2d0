// Render kernel with `bvh-stackless`: the AAC BVH of `bvh`, walked with parent links instead of a stack.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require

#include "include/bvh_stackless.glsl"
#include "include/render_main.glsl"
