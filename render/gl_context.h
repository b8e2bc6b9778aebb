// Headless OpenGL context through EGL with no window system.
// Display selection order: EGL_EXT_platform_device (first device) ->
// EGL_MESA_platform_surfaceless -> EGL_DEFAULT_DISPLAY. Requests OpenGL 3.3 core.
// Works on Mesa llvmpipe (CPU) and on NVIDIA's EGL driver.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace cdlab::render {

struct GlError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class GlContext {
public:
    /// Creates and makes current a context. Throws GlError with one explanatory line.
    /// Costs 70 ms .. 1 s on llvmpipe: create one per process and reuse it.
    static std::unique_ptr<GlContext> create();
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    std::string glRenderer() const;   // GL_RENDERER
    std::string glVersion() const;    // GL_VERSION
    std::string eglPlatform() const;  // "device", "surfaceless" or "default"
    int maxSamples() const;           // GL_MAX_SAMPLES
    /// Makes this context current on the calling thread (Canvas does it before every GL call).
    void makeCurrent();

    /// Internal state (EGL handles, compiled programs, glyph atlases): for render/*.cpp only.
    struct Impl;
    Impl& impl() { return *impl_; }

private:
    explicit GlContext(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace cdlab::render
