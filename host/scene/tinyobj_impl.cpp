// The sanitizer and fuzz builds (VKRAY_TINYOBJ_FROM_HEADER, root CMakeLists.txt) compile
// tinyobjloader here from its header; its functions then take precedence over those of
// libtinyobjloader.so. libFuzzer sees their branches, and their std::vectors carry the same ASan
// annotations as vkray's (_GLIBCXX_SANITIZE_VECTOR): mixing annotated and unannotated copies of
// one std::vector function reports overflows that are not there. Other builds use the library.
#ifdef VKRAY_TINYOBJ_FROM_HEADER
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
#endif
