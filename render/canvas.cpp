// Canvas: records draw commands, renders them into a multisampled FBO in a fixed order and
// reads the picture back. Geometry is projected on the CPU in double precision; wide lines,
// points, arrow heads and glyphs are expanded into screen-space quads on the CPU (a core
// profile has no wide lines), and one small shader (gl_context.cpp) shades them.
#include "render/canvas.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "render/canvas_internal.h"
#include "render/gl_internal.h"
#include "render/pixel_budget.h"

namespace cdlab::render {

Canvas::Canvas(GlContext& context, const CanvasOptions& options) : impl_(nullptr) {
    if (options.width <= 0 || options.height <= 0)
        throw std::invalid_argument("Canvas: size must be positive, got " + std::to_string(options.width) + "x" +
                                    std::to_string(options.height));
    if (options.supersample < 1 || options.supersample > 16)
        throw std::invalid_argument("Canvas: supersample must be 1..16, got " + std::to_string(options.supersample));
    if (options.scale < 1 || options.scale > 16)
        throw std::invalid_argument("Canvas: scale must be 1..16, got " + std::to_string(options.scale));
    impl_ = new Impl(context, options);
    impl_->samples = std::clamp(options.msaaSamples, 1, std::max(1, context.maxSamples()));
}

Canvas::Canvas(GlContext& context, const CanvasOptions& options, const Camera& camera) : Canvas(context, options) {
    setCamera(camera);
}

Canvas::~Canvas() {
    if (impl_->haveTarget) {
        try {
            impl_->context.makeCurrent();
            impl_->context.impl().releaseTarget(impl_->target);
        } catch (...) {  // destructor: never throw; the context frees the FBO with itself
        }
    }
    delete impl_;
}

void Canvas::setCamera(const Camera& camera) { impl_->camera = camera; }
const Camera& Canvas::camera() const { return impl_->camera; }
void Canvas::setBackground(const Color& color) { impl_->background = color; }
int Canvas::width() const { return impl_->options.width; }
int Canvas::height() const { return impl_->options.height; }
int Canvas::samples() const { return impl_->samples; }

bool Canvas::project(const Eigen::Vector3d& p, Eigen::Vector2d& pixel) const {
    const Eigen::Matrix4d vp = impl_->camera.viewProjection(double(width()) / height());
    const Vector4d c = vp * Vector4d(p.x(), p.y(), p.z(), 1.0);
    if (!(c.w() > 0) || !c.allFinite()) return false;
    pixel = {(c.x() / c.w() + 1.0) * 0.5 * width(), (1.0 - c.y() / c.w()) * 0.5 * height()};
    return true;
}

void Canvas::drawMesh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3i>& triangles,
                      const Color& color, bool lit) {
    for (const Eigen::Vector3i& t : triangles)
        for (int k = 0; k < 3; ++k)
            if (t[k] < 0 || std::size_t(t[k]) >= vertices.size())
                throw std::out_of_range("Canvas::drawMesh: triangle index " + std::to_string(t[k]) + " outside 0.." +
                                        std::to_string(int(vertices.size()) - 1));
    impl_->meshes.push_back({vertices, triangles, color, lit});
}

void Canvas::drawPolygon(const std::vector<Eigen::Vector3d>& corners, const Color& color, bool lit) {
    if (corners.size() < 3) return;
    std::vector<Eigen::Vector3i> fan;
    for (int i = 1; i + 1 < int(corners.size()); ++i) fan.emplace_back(0, i, i + 1);
    impl_->meshes.push_back({corners, std::move(fan), color, lit});
}

void Canvas::setStrokeOwner(int owner) { impl_->strokeOwner = owner; }

void Canvas::drawLine(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const LineStyle& style) {
    impl_->overlays.emplace_back(LineCmd{{p, q}, style, false, false, impl_->strokeOwner});
}

void Canvas::drawPolyline(const std::vector<Eigen::Vector3d>& points, bool closed, const LineStyle& style) {
    if (points.size() < 2) return;
    LineCmd cmd{points, style, false, false, impl_->strokeOwner};
    if (closed) cmd.points.push_back(points.front());
    impl_->overlays.emplace_back(std::move(cmd));
}

void Canvas::drawPoint(const Eigen::Vector3d& p, float radiusPx, const Color& color, bool onTop, float outlinePx,
                       const Color& outline) {
    impl_->overlays.emplace_back(PointCmd{p, radiusPx, color, onTop, outlinePx, outline});
}

void Canvas::drawArrow(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const LineStyle& style) {
    impl_->overlays.emplace_back(LineCmd{{p, q}, style, true, false, impl_->strokeOwner});
}

void Canvas::drawText(const Eigen::Vector3d& at, const std::string& text, const TextStyle& style) {
    drawnTextLog().push_back(text);
    impl_->texts.push_back({true, at, Vector2d::Zero(), text, style, {}});
}

void Canvas::drawTextAtAnyOf(const std::vector<Eigen::Vector3d>& at, const std::string& text, const TextStyle& style) {
    if (at.empty()) return;
    drawnTextLog().push_back(text);
    impl_->texts.push_back({true, at.front(), Vector2d::Zero(), text, style, {at.begin() + 1, at.end()}});
}

void Canvas::drawTextPx(double x, double y, const std::string& text, const TextStyle& style) {
    drawnTextLog().push_back(text);
    impl_->texts.push_back({false, Vector3d::Zero(), Vector2d(x, y), text, style, {}});
}

Eigen::Vector2d Canvas::measureText(const std::string& text, const TextStyle& style) const {
    if (!(style.sizePx > 0)) return {0, 0};
    const FontFace& face = impl_->context.impl().font(style.bold);  // metrics only: no GL
    const TextLayout L = layoutText(face, text, style.sizePx);
    return {L.width, L.height};
}

void Canvas::noteQuantity(const std::string& name, const Vector3d& p, const Vector3d& q) {
    impl_->quantities.push_back({name, p, q});
}

void Canvas::noteBody(const std::string& name, const std::vector<Vector3d>& points, const std::string& apartFrom) {
    impl_->bodies.push_back({name, points, apartFrom});
}

void Canvas::noteFeature(const FeatureNote& feature) { impl_->features.push_back(feature); }

void Canvas::noteAxis(const Vector3d& p, const Vector3d& q, bool log) { impl_->axes.push_back({p, q, log}); }

void Canvas::noteSeries(const std::string& name, const Color& color, const Vector3d& at) {
    impl_->series.push_back({name, color, at});
}

void Canvas::clearCommands() {
    impl_->meshes.clear();
    impl_->overlays.clear();
    impl_->texts.clear();
    impl_->quantities.clear();
    impl_->bodies.clear();
    impl_->features.clear();
    impl_->axes.clear();
    impl_->series.clear();
}

RenderStats& renderStats() {
    thread_local RenderStats stats;  // per thread: `cdlab figures` draws on several
    return stats;
}

std::vector<std::string>& drawnTextLog() {
    thread_local std::vector<std::string> log;
    return log;
}

namespace {
double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

thread_local PixelBudget* g_budget = nullptr;  // the innermost budget of this thread
}  // namespace

PixelBudget::PixelBudget(double limit) : limit_(limit), outer_(g_budget) { g_budget = this; }

PixelBudget::~PixelBudget() { g_budget = outer_; }

void PixelBudget::spend(double pixels) {
    PixelBudget* b = g_budget;
    if (!b) return;
    if (b->used_ + pixels > b->limit_)
        throw ImageError("the frames drawn take more than " + std::to_string(static_cast<long long>(b->limit_)) +
                         " rendered pixels together, the limit for one scene (fewer steps, views or queries, or a "
                         "smaller image)");
    b->used_ += pixels;
}

/// The render target for the frame's size (rw x rh) and requested samples: the cached one, or a
/// new one in its place; `samples` becomes what the driver gave.
void Canvas::Impl::prepareTarget(GlContext::Impl& gl) {
    const int requested = std::clamp(options.msaaSamples, 1, std::max(1, gl.maxSamples));
    if (!haveTarget || target.width != rw || target.height != rh || target.requestedSamples != requested) {
        if (haveTarget) gl.releaseTarget(target);
        haveTarget = false;
        target = gl.acquireTarget(rw, rh, requested);
        haveTarget = true;
    }
    samples = target.samples;
}

/// Every vertex of the frame, in drawing order, with where each pass's range starts.
FrameVertices Canvas::Impl::buildFrame() {
    FrameVertices frame;
    std::vector<Vertex> opaque, translucent, overlay, text;
    buildMeshes(opaque, translucent);
    buildOverlays(overlay);
    const int textBase = int(opaque.size() + translucent.size() + overlay.size());
    buildText(text, frame.textRuns, textBase);  // may bake atlases (binds textures): before the draw state
    std::vector<Vertex>& all = frame.all;
    all.reserve(std::size_t(textBase) + text.size());
    for (auto* part : {&opaque, &translucent, &overlay, &text}) all.insert(all.end(), part->begin(), part->end());
    frame.opaque = opaque.size();
    frame.translucent = translucent.size();
    frame.overlay = overlay.size();
    return frame;
}

/// The four passes into the target (opaque meshes, translucent meshes, overlays, text), each with
/// its own depth and blend state.
void Canvas::Impl::renderPasses(GlContext::Impl& gl, const FrameVertices& frame) {
    const std::vector<Vertex>& all = frame.all;
    const GLuint drawFbo = target.samples > 1 ? target.msaaFbo : target.resolveFbo;
    glBindFramebuffer(GL_FRAMEBUFFER, drawFbo);
    glViewport(0, 0, rw, rh);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_MULTISAMPLE);
    glDepthMask(GL_TRUE);
    glClearColor(background.r, background.g, background.b, background.a);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    glUseProgram(gl.program);
    glUniform1i(gl.uniformAtlas, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, gl.whiteTexture);
    glBindVertexArray(gl.vao);
    glBindBuffer(GL_ARRAY_BUFFER, gl.vbo);
    const std::size_t bytes = all.size() * sizeof(Vertex);
    if (bytes > gl.vboCapacity) {
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), nullptr, GL_STREAM_DRAW);
        gl.vboCapacity = bytes;
    }
    if (bytes) glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(bytes), all.data());

    auto draw = [](std::size_t first, std::size_t count) {
        if (count) glDrawArrays(GL_TRIANGLES, GLint(first), GLsizei(count));
    };
    // 1. Opaque meshes: depth test + write. Polygon offset pushes faces back a little so lines
    //    drawn along their edges win the depth test.
    if (is3D()) glEnable(GL_DEPTH_TEST);
    else glDisable(GL_DEPTH_TEST);  // 2D: painter's order
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    draw(0, frame.opaque);
    // 2. Translucent meshes back to front: tested against the opaque depth, not written. Pushed back
    //    one depth unit more than the opaque faces, so a translucent face in the plane of an opaque
    //    one (a highlighted triangle over its mesh) stays behind it everywhere: the pieces it was cut
    //    into (render/translucent_order.h) have new corners whose depth, rounded to float, may
    //    otherwise fall either side of the opaque face's, in stripes. The cost: a translucent face
    //    less than ~1 depth unit in front of an opaque one (1e-4 world units at 5 units from an eye
    //    with near plane 0.01) is hidden there.
    glPolygonOffset(1.0f, 2.0f);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    draw(frame.opaque, frame.translucent);
    // 3. Lines, points, arrows in call order; depth-tested (onTop ones sit at the near plane).
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthFunc(GL_LEQUAL);
    draw(frame.opaque + frame.translucent, frame.overlay);
    // 4. Text on top of everything.
    glDisable(GL_DEPTH_TEST);
    for (const auto& [texture, range] : frame.textRuns) {
        glBindTexture(GL_TEXTURE_2D, texture);
        draw(std::size_t(range.first), std::size_t(range.second));
    }
    glBindTexture(GL_TEXTURE_2D, gl.whiteTexture);
    glDepthMask(GL_TRUE);
}

/// Resolves MSAA, reads back bottom-up, flips to top-first and box-filters supersampling away;
/// `layout` comes along in output pixels.
Image Canvas::Impl::readBack(FigureLayout layout) {
    if (target.samples > 1) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, target.msaaFbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.resolveFbo);
        glBlitFramebuffer(0, 0, rw, rh, 0, 0, rw, rh, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target.resolveFbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    Image raw(rw, rh);
    std::vector<std::uint8_t> rows(raw.rgba.size());
    glReadPixels(0, 0, rw, rh, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    checkGl("rendering and reading back the canvas");
    const std::size_t stride = std::size_t(rw) * 4;
    for (int y = 0; y < rh; ++y)
        std::copy_n(rows.data() + std::size_t(rh - 1 - y) * stride, stride, raw.rgba.data() + std::size_t(y) * stride);
    const int resolve = options.supersample;
    Image out = resolve > 1 ? downsample(raw, resolve) : std::move(raw);
    out.layout = options.scale > 1 ? layout.scaled(options.scale) : std::move(layout);  // in output pixels
    out.scale = options.scale;
    return out;
}

void Canvas::Impl::setFrameSize() {
    ss = options.supersample * options.scale;  // every pixel size is multiplied by this
    rw = options.width * ss;
    rh = options.height * ss;
    viewProjection = camera.viewProjection(double(options.width) / options.height);
}

FigureLayout Canvas::layout() {
    impl_->setFrameSize();
    FigureLayout layout = impl_->layoutTexts();
    return impl_->options.scale > 1 ? layout.scaled(impl_->options.scale) : layout;  // in output pixels
}

Image Canvas::readPixels() {
    Impl& m = *impl_;
    // The rendered size, counted before anything is drawn or read back (m.rw, m.rh are set below).
    const double ss = double(m.options.supersample) * double(m.options.scale);
    PixelBudget::spend(double(m.options.width) * ss * double(m.options.height) * ss);
    RenderStats& stats = renderStats();
    auto t0 = std::chrono::steady_clock::now();
    GlContext::Impl& gl = m.context.impl();
    gl.makeCurrent();
    gl.ensureDrawResources();
    m.setFrameSize();
    m.prepareTarget(gl);
    FigureLayout layout = m.layoutTexts();  // places the point labels: before any vertex is built
    const FrameVertices frame = m.buildFrame();

    stats.buildSeconds += secondsSince(t0);
    t0 = std::chrono::steady_clock::now();
    m.renderPasses(gl, frame);

    if (stats.profiling) glFinish();
    stats.drawSeconds += secondsSince(t0);
    t0 = std::chrono::steady_clock::now();
    Image out = m.readBack(std::move(layout));
    stats.readbackSeconds += secondsSince(t0);
    ++stats.frames;
    return out;
}

}  // namespace cdlab::render
