// The ONE translation unit that compiles the stb implementations (stb_image for PNG decoding,
// stb_image_write for PNG encoding, stb_truetype for glyph rasterization). Every other file
// includes the headers without the *_IMPLEMENTATION macros.
// stb is third-party code: its own warnings are silenced here only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"

#define STBI_ONLY_PNG
#define STBI_NO_STDIO  // we read files ourselves to report precise errors
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#define STBI_WRITE_NO_STDIO  // encoded to memory, then written atomically by image.cpp
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#define STB_RECT_PACK_IMPLEMENTATION
#include <stb_rect_pack.h>
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>

#pragma GCC diagnostic pop
