// Render kernel with the `bvh-sphere` accelerator: AAC with sphere containers (Mahmuda 2017's
// box/sphere experiment): the walks of `bvh` with a sphere test per child.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#define VKRAY_BVH_SPHERES
#include "include/bvh_traversal.glsl"
#include "include/render_main.glsl"
