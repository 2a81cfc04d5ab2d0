// tinygltf as vkray uses it: images are neither decoded (no stb_image) nor read from their files,
// because vkray samples no textures; every source that includes tiny_gltf.h includes it through
// this header, so the declarations and tinygltf_impl.cpp's definitions agree.
#pragma once

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
