// The one translation unit that compiles stb_image, stb_image_write and stb_image_resize. Everything else in
// Penumbra (the image code, and the glTF loader through tinygltf) includes the headers without
// the implementation macros and links against these definitions.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_RESIZE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_resize.h>
#include <stb_image_write.h>
