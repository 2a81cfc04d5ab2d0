// tinygltf's definitions (it is header-only), compiled alone: its macros must not reach other sources.
#define TINYGLTF_IMPLEMENTATION
#include "scene/tinygltf_config.h"
