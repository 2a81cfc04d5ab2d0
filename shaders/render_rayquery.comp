// Render kernel with the `rayquery` accelerator: the device driver's own structure and traversal
// (VK_KHR_ray_query), a yardstick for vkray's traversals on the same rays and the same shading.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_EXT_ray_query : require

#include "include/ray_query.glsl"
#include "include/render_main.glsl"
