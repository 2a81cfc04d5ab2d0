// Render kernel with the kd-backtrack traversal of the SAH kd-tree (include/kd_backtrack.glsl).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#include "include/kd_backtrack.glsl"
#include "include/render_main.glsl"
