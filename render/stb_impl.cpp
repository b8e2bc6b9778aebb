// The ONE translation unit that compiles the stb implementations (stb_image for PNG decoding,
// stb_truetype for glyph rasterization). Every other file
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

#include <cstddef>
#include <cstdlib>

// stb_image's allocations, bounded: a PNG that is small on disk can still ask its inflater for a
// huge buffer. No single allocation may exceed 1 GiB (a 8192 x 8192 RGBA golden, the largest that
// readPng accepts, is 256 MiB); past that the decode fails cleanly ("outofmem").
namespace {
constexpr std::size_t kMaxStbAllocation = std::size_t(1) << 30;
void* boundedMalloc(std::size_t size) { return size > kMaxStbAllocation ? nullptr : std::malloc(size); }
void* boundedRealloc(void* p, std::size_t size) { return size > kMaxStbAllocation ? nullptr : std::realloc(p, size); }
}  // namespace
#define STBI_MALLOC(size) boundedMalloc(size)
#define STBI_REALLOC(p, size) boundedRealloc(p, size)
#define STBI_FREE(p) std::free(p)

#define STBI_ONLY_PNG
#define STBI_NO_STDIO  // we read files ourselves to report precise errors
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#define STB_RECT_PACK_IMPLEMENTATION
#include <stb_rect_pack.h>
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>

#pragma GCC diagnostic pop
