// Render kernel with the kd-restart traversal of the SAH kd-tree (include/kd_restart.glsl).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#include "include/kd_restart.glsl"
#include "include/render_main.glsl"
