// Render kernel with the `brute` accelerator: every ray against every triangle.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#include "include/brute_force.glsl"
#include "include/render_main.glsl"
