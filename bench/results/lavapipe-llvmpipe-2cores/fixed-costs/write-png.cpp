// Times writeColorImage of a 640x480 render-like image (gradients, noise, values above 1), five
// times. Build from the repository root after `make build`:
//   g++ -std=c++20 -O2 -Ihost -Ishaders -Ibuild/generated bench/results/lavapipe-llvmpipe-2cores/fixed-costs/write-png.cpp \
//       build/libvkray_base.a -ltbb -lOpenEXR-3_1 -lImath-3_1 -lIex-3_1 -lz -o /tmp/write-png
// (docs/benchmarks.md, "What a small render pays before and after its kernels"; write-png.txt).
#include <chrono>
#include <cstdio>
#include <random>
#include "image/image_io.h"
int main(int argc, char** argv) {
    const int w = argc > 1 ? atoi(argv[1]) : 640, h = argc > 2 ? atoi(argv[2]) : 480;
    // a render-like image: smooth gradients, some noise, some >1 values
    std::vector<glm::vec3> c(size_t(w) * h);
    std::mt19937 rng(1); std::uniform_real_distribution<float> u(0, 1);
    for (int j = 0; j < h; ++j) for (int i = 0; i < w; ++i)
        c[size_t(j) * w + i] = glm::vec3(float(i) / w, float(j) / h, 0.5f * u(rng) * (i % 7 == 0)) * 1.1f;
    for (int r = 0; r < 5; ++r) {
        auto t0 = std::chrono::steady_clock::now();
        vkray::writeColorImage("/tmp/write-png.png", w, h, c);
        auto t1 = std::chrono::steady_clock::now();
        std::printf("%.1f ms\n", std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
}
