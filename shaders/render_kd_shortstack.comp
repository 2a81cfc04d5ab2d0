// Render kernel with the short-stack traversal of the SAH kd-tree (include/kd_stack.glsl).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#define VKRAY_KD_SHORT_STACK
#include "include/kd_stack.glsl"
#include "include/render_main.glsl"
