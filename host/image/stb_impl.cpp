// The one translation unit that compiles the stb image reader and writer (single-header libraries:
// exactly one .cpp of the program may define the *_IMPLEMENTATION macros). Anyone else who needs
// stb_image just includes the header without the macros. Full default configuration, so every
// declaration in the headers has a definition.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_write.h>
