// Render kernel with kd-restart going on by ropes over the SAH kd-tree (include/kd_restart.glsl).
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#define VKRAY_KD_ROPES
#include "include/kd_restart.glsl"
#include "include/render_main.glsl"
