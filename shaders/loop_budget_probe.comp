// The loop-budget probe (host/gpu/loop_budget.cpp): one invocation counts its passes through a loop
// of `bound` iterations and stores the count. The bound comes from a push constant, so that no
// compiler can count the passes for it. llvmpipe of Mesa 22.3 ends every loop of an invocation once
// its loops together ran 65535 iterations (trace_status.glsl): there the count falls short.
#version 460

layout(local_size_x = 1) in;
layout(std430, set = 0, binding = 0) buffer Passes { uint passes; };
layout(push_constant) uniform Bound { uint bound; };

void main() {
    uint n = 0u;
    for (uint i = 0u; i < bound; ++i) ++n;
    passes = n;
}
