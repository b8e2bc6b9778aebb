// Headless OpenGL 3.3 core through EGL, without any window system.
// Display order: EGL_EXT_platform_device (first device; NVIDIA and Mesa both expose it)
// -> EGL_MESA_platform_surfaceless -> EGL_DEFAULT_DISPLAY. A surfaceless context
// (EGL_KHR_surfaceless_context) is used when offered, else a 1x1 pbuffer: all drawing goes
// to framebuffer objects anyway. No environment variables are read or needed.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "render/gl_internal.h"

// CDLAB_FONT_DIR: the folder holding DejaVuSans.ttf, found by render/CMakeLists.txt (find_path).

namespace cdlab::render {

namespace {

std::string eglErrorName(EGLint e) {
    switch (e) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
        case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
        case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
        default: {
            char buf[32];
            std::snprintf(buf, sizeof buf, "EGL error 0x%04x", unsigned(e));
            return buf;
        }
    }
}

std::string eglFailure(const char* call) { return std::string(call) + " failed (" + eglErrorName(eglGetError()) + ")"; }

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

// EGL displays are per-process singletons per (platform, device), and eglInitialize on an
// initialized display only returns it again. We never call eglTerminate: it would kill every
// other GlContext on the same display, and on Mesa it unloads the llvmpipe driver, which leaks
// LLVM state that LeakSanitizer reports. Contexts and surfaces are destroyed; the display stays.

/// Initializes `display` and creates a current 3.3 core context on it. Returns "" on success,
/// otherwise why not, in a few words.
std::string createOn(EGLDisplay display, GlContext::Impl& out) {
    if (display == EGL_NO_DISPLAY) return eglFailure("eglGetPlatformDisplay");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) return eglFailure("eglInitialize");
    const char* ext = eglQueryString(display, EGL_EXTENSIONS);
    if (!(major > 1 || (major == 1 && minor >= 5)) && !hasExtension(ext, "EGL_KHR_create_context"))
        return "EGL " + std::to_string(major) + "." + std::to_string(minor) +
               " without EGL_KHR_create_context cannot request a core profile";
    if (!eglBindAPI(EGL_OPENGL_API)) return eglFailure("eglBindAPI(EGL_OPENGL_API)");

    const bool surfaceless = hasExtension(ext, "EGL_KHR_surfaceless_context");
    EGLConfig config = nullptr;
    EGLint count = 0;
    // Pbuffer-capable first (works everywhere); surfaceless-only configs as a second chance.
    for (EGLint surfaceType : {EGLint(EGL_PBUFFER_BIT), EGLint(0)}) {
        if (surfaceType == 0 && !surfaceless) break;
        const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, surfaceType, EGL_NONE};
        if (eglChooseConfig(display, attribs, &config, 1, &count) && count > 0) break;
    }
    if (count < 1) return "eglChooseConfig found no OpenGL-renderable config (" + eglErrorName(eglGetError()) + ")";

    const EGLint contextAttribs[] = {
        EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
    if (context == EGL_NO_CONTEXT) return eglFailure("eglCreateContext(OpenGL 3.3 core)");
    EGLSurface surface = EGL_NO_SURFACE;
    if (!surfaceless) {
        const EGLint pbufferAttribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        surface = eglCreatePbufferSurface(display, config, pbufferAttribs);
        if (surface == EGL_NO_SURFACE) {
            std::string why = eglFailure("eglCreatePbufferSurface(1x1) (no EGL_KHR_surfaceless_context)");
            eglDestroyContext(display, context);
            return why;
        }
    }
    if (!eglMakeCurrent(display, surface, surface, context)) {
        std::string why = eglFailure("eglMakeCurrent");
        if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
        eglDestroyContext(display, context);
        return why;
    }
    out.display = display;
    out.context = context;
    out.surface = surface;
    return "";
}

}  // namespace

const char* glErrorName(GLenum error) {
    switch (error) {
        case GL_NO_ERROR: return "GL_NO_ERROR";
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        default: return "unknown GL error";
    }
}

void checkGl(const char* step) {
    const GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        while (glGetError() != GL_NO_ERROR) {}  // drain, so the next check reports its own step
        throw GlError(std::string("OpenGL: ") + step + " failed (" + glErrorName(e) + ")");
    }
}

std::unique_ptr<GlContext> GlContext::create() {
    auto impl = std::make_unique<Impl>();
    // Client extensions (EGL_EXT_client_extensions): NULL on very old EGL, then only the default display.
    const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!clientExt) eglGetError();  // clear EGL_BAD_DISPLAY
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    const bool havePlatformBase = getPlatformDisplay && (hasExtension(clientExt, "EGL_EXT_platform_base") ||
                                                         hasExtension(clientExt, "EGL_EXT_client_extensions"));
    std::string failures;
    auto attempt = [&](const char* platform, auto getDisplay) {
        const std::string why = createOn(getDisplay(), *impl);
        if (why.empty()) {
            impl->platform = platform;
            return true;
        }
        failures += std::string(failures.empty() ? "" : "; ") + platform + ": " + why;
        return false;
    };

    bool ok = false;
    if (!havePlatformBase || !queryDevices || !hasExtension(clientExt, "EGL_EXT_platform_device")) {
        failures = "device: EGL_EXT_platform_device not offered";
    } else {
        EGLDeviceEXT devices[16];
        EGLint numDevices = 0;
        if (!queryDevices(16, devices, &numDevices) || numDevices < 1)
            failures = "device: eglQueryDevicesEXT found no device (" + eglErrorName(eglGetError()) + ")";
        else ok = attempt("device", [&] { return getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr); });
    }
    if (!ok) {
        if (havePlatformBase && hasExtension(clientExt, "EGL_MESA_platform_surfaceless"))
            ok = attempt("surfaceless", [&] {
                return getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            });
        else failures += "; surfaceless: EGL_MESA_platform_surfaceless not offered";
    }
    if (!ok) ok = attempt("default", [] { return eglGetDisplay(EGL_DEFAULT_DISPLAY); });
    if (!ok) throw GlError("EGL: no headless OpenGL 3.3 core context: " + failures);

    auto str = [](GLenum name) {
        const GLubyte* s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    impl->renderer = str(GL_RENDERER);
    impl->version = str(GL_VERSION);
    GLint glMajor = 0, glMinor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &glMajor);
    glGetIntegerv(GL_MINOR_VERSION, &glMinor);
    glGetIntegerv(GL_MAX_SAMPLES, &impl->maxSamples);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &impl->maxRenderbufferSize);
    if (glMajor * 10 + glMinor < 33) {
        const std::string got = impl->version;
        // The destructor releases the context.
        GlContext doomed(std::move(impl));
        throw GlError("OpenGL: got version " + got + ", need 3.3 core");
    }
    glGetError();  // a fresh context has no error; clear anything the queries left
    return std::unique_ptr<GlContext>(new GlContext(std::move(impl)));
}

GlContext::GlContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

GlContext::~GlContext() {
    Impl& m = *impl_;
    if (m.display == EGL_NO_DISPLAY) return;
    m.makeCurrent();
    for (RenderTarget& t : m.targetPool) m.destroyTarget(t);
    for (auto& [key, atlas] : m.atlases) glDeleteTextures(1, &atlas->texture);
    if (m.whiteTexture) glDeleteTextures(1, &m.whiteTexture);
    if (m.vbo) glDeleteBuffers(1, &m.vbo);
    if (m.vao) glDeleteVertexArrays(1, &m.vao);
    if (m.program) glDeleteProgram(m.program);
    eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (m.surface != EGL_NO_SURFACE) eglDestroySurface(m.display, m.surface);
    eglDestroyContext(m.display, m.context);
}

std::string GlContext::glRenderer() const { return impl_->renderer; }
std::string GlContext::glVersion() const { return impl_->version; }
std::string GlContext::eglPlatform() const { return impl_->platform; }
int GlContext::maxSamples() const { return impl_->maxSamples; }
void GlContext::makeCurrent() { impl_->makeCurrent(); }

void GlContext::Impl::makeCurrent() {
    if (eglGetCurrentContext() == context) return;
    if (!eglMakeCurrent(display, surface, surface, context)) throw GlError("EGL: " + eglFailure("eglMakeCurrent"));
}

// ---------------------------------------------------------------------------------------------
// The one shader program. Everything arrives as triangles with the vertex already in clip space
// (projected on the CPU in double precision, so large world offsets do not lose precision in
// float). The fragment shader has four modes:
//   0 flat colour (meshes, polygons, arrow heads)
//   1 capsule: thick line with round caps, analytic anti-aliasing, optional dashes
//   2 disc with outline (points)
//   3 glyph from the atlas (text)
// Line/disc coordinates are in render pixels and interpolated without perspective.
namespace {
const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec4 aPos;
layout(location = 1) in vec4 aColor;
layout(location = 2) in vec4 aColor2;
layout(location = 3) in vec4 aLocal;
layout(location = 4) in vec4 aParam;
flat out vec4 vColor;
flat out vec4 vColor2;
flat out vec4 vParam;
noperspective out vec4 vLocal;
void main() {
    gl_Position = aPos;
    vColor = aColor;
    vColor2 = aColor2;
    vParam = aParam;
    vLocal = aLocal;
}
)";

const char* kFragmentShader = R"(#version 330 core
flat in vec4 vColor;
flat in vec4 vColor2;
flat in vec4 vParam;
noperspective in vec4 vLocal;
uniform sampler2D uAtlas;
out vec4 fragColor;
void main() {
    int mode = int(vParam.x + 0.5);
    vec4 c = vColor;
    if (mode == 1) {
        // local = (u along the segment, v across, dash phase), px; param = (1, half width, length, dash)
        float u = vLocal.x, v = vLocal.y, halfW = vParam.y, len = vParam.z, dash = vParam.w;
        float dAlong = max(max(-u, u - len), 0.0);  // outside the segment: round cap
        if (dash > 0.0) {
            // Dashes of length `dash` every 2*dash; each dash is a capsule whose core is shortened
            // by the cap radius so the visible dash keeps its length.
            float period = 2.0 * dash;
            float e = min(halfW, 0.5 * dash);
            float t = mod(u + vLocal.z, period);
            float toThis = max(max(e - t, t - (dash - e)), 0.0);
            float toNext = e + period - t;
            dAlong = max(dAlong, min(toThis, toNext));
        }
        float dist = length(vec2(dAlong, v));
        c.a *= clamp(halfW + 0.5 - dist, 0.0, 1.0);  // 1 px wide coverage ramp
    } else if (mode == 2) {
        // local = offset from the centre, px; param = (2, radius, outline width)
        float r = length(vLocal.xy);
        float radius = vParam.y, outline = vParam.z;
        if (outline > 0.0) c = mix(vColor, vColor2, clamp(r - (radius - outline) + 0.5, 0.0, 1.0));
        c.a *= clamp(radius + 0.5 - r, 0.0, 1.0);
    } else if (mode == 3) {
        c.a *= texture(uAtlas, vLocal.xy).r;
    }
    if (c.a <= 0.0) discard;
    fragColor = c;
}
)";

// The driver's message for a shader that failed to compile or a program that failed to link
// (getLog: glGetShaderInfoLog or glGetProgramInfoLog), cut to 2 KiB.
template <class GetLog>
std::string infoLog(GLuint object, GetLog getLog) {
    char log[2048] = {0};
    getLog(object, sizeof log - 1, nullptr, log);
    return log;
}

GLuint compile(GLenum type, const char* source, const char* what) {
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        std::string line = infoLog(shader, glGetShaderInfoLog);
        glDeleteShader(shader);
        for (char& ch : line)
            if (ch == '\n') ch = ' ';
        throw GlError(std::string("OpenGL: compiling the ") + what + " shader failed: " + line);
    }
    return shader;
}
}  // namespace

void GlContext::Impl::ensureDrawResources() {
    if (program) return;
    const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader, "vertex");
    const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader, "fragment");
    program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        const std::string log = infoLog(program, glGetProgramInfoLog);
        glDeleteProgram(program);
        program = 0;
        throw GlError(std::string("OpenGL: linking the shader program failed: ") + log);
    }
    uniformAtlas = glGetUniformLocation(program, "uAtlas");

    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    constexpr GLsizei stride = 20 * sizeof(float);  // 5 x vec4, see Vertex in canvas_internal.h
    for (GLuint i = 0; i < 5; ++i) {
        glEnableVertexAttribArray(i);
        glVertexAttribPointer(i, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(std::uintptr_t(i * 16)));
    }
    // 1x1 white texture bound whenever no atlas is (a sampler must always have a complete texture).
    glGenTextures(1, &whiteTexture);
    glBindTexture(GL_TEXTURE_2D, whiteTexture);
    const unsigned char white = 255;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, 1, 1, 0, GL_RED, GL_UNSIGNED_BYTE, &white);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    checkGl("creating the shared drawing resources");
}

// ---------------------------------------------------------------------------------------------
// Fonts and glyph atlases.

void GlContext::Impl::loadFonts() {
    if (fontsLoaded) return;
    const char* names[2] = {"DejaVuSans.ttf", "DejaVuSans-Bold.ttf"};
    for (int i = 0; i < 2; ++i) {
        const std::string path = std::string(CDLAB_FONT_DIR) + "/" + names[i];
        std::ifstream in(path, std::ios::binary);
        FontFace& f = fonts[i];
        f.ttf.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        if (f.ttf.empty()) throw GlError("font: cannot read '" + path + "' (install fonts-dejavu-core)");
        if (!stbtt_InitFont(&f.info, f.ttf.data(), stbtt_GetFontOffsetForIndex(f.ttf.data(), 0)))
            throw GlError("font: '" + path + "' is not a TrueType font stb_truetype can read");
        stbtt_GetFontVMetrics(&f.info, &f.ascent, &f.descent, &f.lineGap);
        for (int cp : atlasCodepoints())
            if (stbtt_FindGlyphIndex(&f.info, cp) != 0) f.available.insert(std::uint32_t(cp));
    }
    fontsLoaded = true;
}

const FontFace& GlContext::Impl::font(bool bold) {
    loadFonts();
    return fonts[bold ? 1 : 0];
}

const std::vector<int>& atlasCodepoints() {
    static const std::vector<int> list = [] {
        std::vector<int> cps;
        for (int c = 32; c < 127; ++c) cps.push_back(c);
        for (int c = 0xA0; c <= 0xFF; ++c) cps.push_back(c);      // · × ± ° ² ³ ...
        for (int c = 0x391; c <= 0x3A9; ++c) cps.push_back(c);    // Greek capitals
        for (int c = 0x3B1; c <= 0x3C9; ++c) cps.push_back(c);    // Greek small
        for (int c = 0x2070; c <= 0x209C; ++c) cps.push_back(c);  // super/subscripts
        for (int c : {0x03D5, 0x03F5, 0x2013, 0x2014, 0x2016, 0x2020, 0x2022, 0x2026, 0x2032, 0x2033, 0x2190, 0x2191,
                      0x2192, 0x2193, 0x2194, 0x21D0, 0x21D2, 0x21D4, 0x2200, 0x2202, 0x2203, 0x2205, 0x2207, 0x2208,
                      0x2209, 0x2211, 0x2212, 0x2218, 0x2219, 0x221A, 0x221E, 0x2220, 0x2225, 0x2227, 0x2228, 0x2229,
                      0x222A, 0x222B, 0x2248, 0x2260, 0x2261, 0x2264, 0x2265, 0x2282, 0x2283, 0x2286, 0x2287, 0x2295,
                      0x2296, 0x2297, 0x22C5, 0x25A0, 0x25A1, 0x25B3, 0x25CB, 0x27E8, 0x27E9})
            cps.push_back(c);
        return cps;
    }();
    return list;
}

GlyphAtlas& GlContext::Impl::atlas(bool bold, int pixelSize) {
    const auto key = std::make_pair(bold ? 1 : 0, pixelSize);
    auto it = atlases.find(key);
    if (it != atlases.end()) return *it->second;
    const FontFace& face = font(bold);
    // Only code points the face has: stbtt_PackFontRanges reports failure for skipped ones.
    std::vector<int> codepoints;
    for (int cp : atlasCodepoints())
        if (face.available.count(std::uint32_t(cp))) codepoints.push_back(cp);
    std::vector<stbtt_packedchar> packed(codepoints.size());
    stbtt_pack_range range{};
    range.font_size = float(pixelSize);
    range.array_of_unicode_codepoints = const_cast<int*>(codepoints.data());
    range.num_chars = int(codepoints.size());
    range.chardata_for_range = packed.data();

    // Smallest power-of-two square that fits: estimate, then grow on failure.
    int side = 64;
    while (double(side) * side < 0.8 * codepoints.size() * double(pixelSize + 2) * (pixelSize + 2)) side *= 2;
    std::vector<unsigned char> bitmap;
    for (;; side *= 2) {
        if (side > 8192) throw GlError("font: glyph atlas for " + std::to_string(pixelSize) + " px exceeds 8192x8192");
        bitmap.assign(std::size_t(side) * side, 0);
        stbtt_pack_context pc;
        if (!stbtt_PackBegin(&pc, bitmap.data(), side, side, 0, 1, nullptr))
            throw GlError("font: stbtt_PackBegin failed");
        stbtt_PackSetOversampling(&pc, 1, 1);  // integer-aligned glyphs: crisp and deterministic
        const int ok = stbtt_PackFontRanges(&pc, face.ttf.data(), 0, &range, 1);
        stbtt_PackEnd(&pc);
        if (ok) break;
    }
    auto a = std::make_unique<GlyphAtlas>();
    a->width = a->height = side;
    a->pixelSize = float(pixelSize);
    for (std::size_t i = 0; i < codepoints.size(); ++i) a->glyphs.emplace(std::uint32_t(codepoints[i]), packed[i]);
    glGenTextures(1, &a->texture);
    glBindTexture(GL_TEXTURE_2D, a->texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, side, side, 0, GL_RED, GL_UNSIGNED_BYTE, bitmap.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    checkGl("uploading a glyph atlas");
    return *atlases.emplace(key, std::move(a)).first->second;
}

// ---------------------------------------------------------------------------------------------
// Render targets.

namespace {
const char* framebufferStatusName(GLenum status) {
    switch (status) {
        case GL_FRAMEBUFFER_COMPLETE: return "GL_FRAMEBUFFER_COMPLETE";
        case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
        case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
        case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
        case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
        case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
        default: return "unknown framebuffer status";
    }
}

/// Colour + depth renderbuffers on a new FBO; returns the completeness status.
GLenum makeFramebuffer(int w, int h, int samples, GLuint& fbo, GLuint& color, GLuint& depth) {
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &color);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    glGenRenderbuffers(1, &depth);
    glBindRenderbuffer(GL_RENDERBUFFER, depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    while (glGetError() != GL_NO_ERROR) {
    }  // an unsupported sample count reports GL_INVALID_VALUE here; the status says it all
    return status;
}

void deleteFramebuffer(GLuint& fbo, GLuint& color, GLuint& depth) {
    if (fbo) glDeleteFramebuffers(1, &fbo);
    if (color) glDeleteRenderbuffers(1, &color);
    if (depth) glDeleteRenderbuffers(1, &depth);
    fbo = color = depth = 0;
}
}  // namespace

RenderTarget GlContext::Impl::acquireTarget(int width, int height, int samples) {
    for (auto it = targetPool.begin(); it != targetPool.end(); ++it)
        if (it->width == width && it->height == height && it->requestedSamples == samples) {
            RenderTarget t = *it;
            targetPool.erase(it);
            return t;
        }
    if (width > maxRenderbufferSize || height > maxRenderbufferSize)
        throw GlError("OpenGL: render size " + std::to_string(width) + "x" + std::to_string(height) +
                      " exceeds GL_MAX_RENDERBUFFER_SIZE " + std::to_string(maxRenderbufferSize) +
                      " (lower the supersampling factor)");
    RenderTarget t;
    t.width = width;
    t.height = height;
    t.requestedSamples = t.samples = samples;
    const GLenum status = makeFramebuffer(width, height, 0, t.resolveFbo, t.resolveColor, t.resolveDepth);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        destroyTarget(t);
        throw GlError(std::string("OpenGL: ") + std::to_string(width) + "x" + std::to_string(height) +
                      " framebuffer incomplete (" + framebufferStatusName(status) + ")");
    }
    // Some drivers accept a sample count <= GL_MAX_SAMPLES yet leave the FBO incomplete for a
    // format: halve until complete (reported through Canvas::samples()).
    while (t.samples > 1) {
        const GLenum msStatus = makeFramebuffer(width, height, t.samples, t.msaaFbo, t.msaaColor, t.msaaDepth);
        if (msStatus == GL_FRAMEBUFFER_COMPLETE) break;
        deleteFramebuffer(t.msaaFbo, t.msaaColor, t.msaaDepth);
        t.samples /= 2;
    }
    if (t.samples < 1) t.samples = 1;
    checkGl("creating the framebuffers");
    return t;
}

void GlContext::Impl::releaseTarget(RenderTarget target) {
    constexpr std::size_t kPoolSize = 4;  // a few sizes are typical (figure, thumbnail, test)
    targetPool.push_back(target);
    if (targetPool.size() > kPoolSize) {
        destroyTarget(targetPool.front());
        targetPool.erase(targetPool.begin());
    }
}

void GlContext::Impl::destroyTarget(RenderTarget& t) {
    deleteFramebuffer(t.msaaFbo, t.msaaColor, t.msaaDepth);
    deleteFramebuffer(t.resolveFbo, t.resolveColor, t.resolveDepth);
}

}  // namespace cdlab::render
