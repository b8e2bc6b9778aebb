// Private to render/*.cpp: the GL/EGL headers and the per-context state behind GlContext.
// Not installed for other folders (it needs the stb include path and GL headers).
#pragma once

#define EGL_NO_X11  // no X11 types through eglplatform.h
#define MESA_EGL_NO_X11_HEADERS
#include <EGL/egl.h>
#include <EGL/eglext.h>

// Core-profile entry points are exported by GLVND's libOpenGL on Mesa and NVIDIA alike.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_rect_pack.h>
#include <stb_truetype.h>
#pragma GCC diagnostic pop

#include "render/gl_context.h"

namespace cdlab::render {

/// A loaded TrueType face (bytes must outlive `info`).
struct FontFace {
    std::vector<unsigned char> ttf;
    stbtt_fontinfo info{};
    int ascent = 0, descent = 0, lineGap = 0;     // font units
    std::unordered_set<std::uint32_t> available;  // atlas code points this face has glyphs for
};

/// Code points baked into every atlas: ASCII, Latin-1, Greek, sub/superscripts, math symbols.
const std::vector<int>& atlasCodepoints();

/// Glyphs of one face at one pixel size, packed into a single-channel texture.
struct GlyphAtlas {
    GLuint texture = 0;
    int width = 0, height = 0;
    float pixelSize = 0;  // stbtt "pixel height": ascent - descent in pixels
    std::unordered_map<std::uint32_t, stbtt_packedchar> glyphs;
};

/// Multisampled draw target + single-sample resolve target of one size; pooled per context.
struct RenderTarget {
    int width = 0, height = 0, requestedSamples = 0, samples = 0;  // samples: effective
    GLuint msaaFbo = 0, msaaColor = 0, msaaDepth = 0;              // msaaFbo == 0 when samples <= 1
    GLuint resolveFbo = 0, resolveColor = 0, resolveDepth = 0;
};

struct GlContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;  // 1x1 pbuffer only without EGL_KHR_surfaceless_context
    std::string platform;
    std::string renderer, version;
    int maxSamples = 1;
    int maxRenderbufferSize = 0;

    // Shared drawing resources, created on first use and reused by every Canvas.
    GLuint program = 0;
    GLint uniformAtlas = -1;
    GLuint vao = 0, vbo = 0;
    std::size_t vboCapacity = 0;
    GLuint whiteTexture = 0;

    FontFace fonts[2];  // regular, bold; loaded on first use
    bool fontsLoaded = false;
    std::map<std::pair<int, int>, std::unique_ptr<GlyphAtlas>> atlases;  // (bold, pixel size)
    std::vector<RenderTarget> targetPool;                                // released by destroyed canvases

    void makeCurrent();
    void ensureDrawResources();
    void loadFonts();
    const FontFace& font(bool bold);
    GlyphAtlas& atlas(bool bold, int pixelSize);
    RenderTarget acquireTarget(int width, int height, int samples);
    void releaseTarget(RenderTarget target);
    void destroyTarget(RenderTarget& target);
};

/// "GL_INVALID_ENUM" etc.
const char* glErrorName(GLenum error);
/// Throws GlError "<step>: <GL error name>" if glGetError() reports something.
void checkGl(const char* step);

}  // namespace cdlab::render
