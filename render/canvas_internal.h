// Private to render/canvas*.cpp: the command records, the vertex format and Canvas::Impl, shared by
// canvas.cpp (public API, readPixels and its passes), canvas_text.cpp (text layout and label
// placement) and canvas_build.cpp (vertices for every recorded command).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "render/canvas.h"
#include "render/gl_internal.h"

namespace cdlab::render {

namespace canvas_detail {

using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::Vector4d;

/// One vertex of the shared program: 5 x vec4 (layout set in GlContext::Impl::ensureDrawResources).
struct Vertex {
    float pos[4];     // clip space
    float color[4];   // fill
    float color2[4];  // disc outline
    float local[4];   // mode-specific, interpolated without perspective
    float param[4];   // mode, then mode-specific constants
};
static_assert(sizeof(Vertex) == 20 * sizeof(float));

enum Mode { kFlat = 0, kCapsule = 1, kDisc = 2, kGlyph = 3 };

inline void set4(float* dst, double a, double b, double c, double d) {
    dst[0] = float(a), dst[1] = float(b), dst[2] = float(c), dst[3] = float(d);
}
inline void setColor(float* dst, const Color& c) { dst[0] = c.r, dst[1] = c.g, dst[2] = c.b, dst[3] = c.a; }

struct MeshCmd {
    std::vector<Vector3d> vertices;
    std::vector<Eigen::Vector3i> triangles;
    Color color;
    bool lit;
};
struct LineCmd {
    std::vector<Vector3d> points;  // closed polylines repeat the first point at the end
    LineStyle style;
    bool arrow;
    bool pixelSpace = false;  // points are output pixels (x, y, 0): leader lines of placed labels
    int owner = 0;            // Canvas::setStrokeOwner at the time it was drawn (0: none)
};
struct PointCmd {
    Vector3d p;
    float radiusPx;
    Color color;
    bool onTop;
    float outlinePx;
    Color outline;
};
struct TextCmd {
    bool world;
    Vector3d at;  // world
    Vector2d px;  // output pixels
    std::string text;
    TextStyle style;
    std::vector<Vector3d> alsoAt;  // world: other points the label may name instead (Canvas::drawTextAtAnyOf)
};

/// A laid-out line of glyphs: code points (already mapped to what the atlas has) and pen x.
struct TextLayout {
    struct Line {
        std::vector<std::uint32_t> codepoints;
        std::vector<double> penX;  // relative to the line start, px
        double width = 0;
    };
    std::vector<Line> lines;
    double width = 0, height = 0;  // box, px
    double ascent = 0, lineHeight = 0;
};

/// UTF-8 to code points; malformed bytes become U+FFFD (drawn as '?').
std::vector<std::uint32_t> decodeUtf8(const std::string& s);
/// Layout at `sizePx` (stb "pixel height": ascent - descent). The same code measures (output
/// pixels) and draws (render pixels), so the measured box is the drawn box.
TextLayout layoutText(const FontFace& face, const std::string& text, double sizePx);
/// Top-left of the text box whose `anchor` point sits at (x, y); horizontal alignment of lines.
Vector2d boxOrigin(Anchor anchor, double x, double y, double w, double h, double& align);

/// One frame's vertices, in drawing order: `opaque` opaque-mesh vertices, then `translucent`
/// translucent ones, then `overlay` line / point / arrow ones, then glyph quads, drawn in
/// `textRuns` (atlas texture, (first vertex, count)).
struct FrameVertices {
    std::vector<Vertex> all;
    std::size_t opaque = 0, translucent = 0, overlay = 0;
    std::vector<std::pair<GLuint, std::pair<int, int>>> textRuns;
};

}  // namespace canvas_detail

using namespace canvas_detail;

struct Canvas::Impl {
    GlContext& context;
    CanvasOptions options;
    Camera camera;
    Color background = roleColor(Role::Background);
    std::vector<MeshCmd> meshes;
    std::vector<std::variant<LineCmd, PointCmd>> overlays;
    std::vector<TextCmd> texts;
    struct QuantityCmd {
        std::string name;
        Eigen::Vector3d p, q;
    };
    std::vector<QuantityCmd> quantities;  // noteQuantity: measured on the picture by layoutTexts
    struct BodyCmd {
        std::string name;
        std::vector<Eigen::Vector3d> points;
        std::string apartFrom;
    };
    std::vector<BodyCmd> bodies;  // noteBody: projected and hulled by layoutTexts
    std::vector<FeatureNote> features;  // noteFeature: seen from the camera by recordNotes
    struct AxisCmd {
        Eigen::Vector3d p, q;
        bool log;
    };
    std::vector<AxisCmd> axes;  // noteAxis
    struct SeriesCmd {
        std::string name;
        Color color;
        Eigen::Vector3d at;
    };
    std::vector<SeriesCmd> series;  // noteSeries
    int strokeOwner = 0;  // setStrokeOwner: the owner of the strokes drawn next
    // Per frame, from layoutTexts(): where each text goes (its offset after placement; none: not
    // drawn) and the leader lines of labels moved away from their points.
    std::vector<std::optional<Vector2d>> textOffsets;
    std::vector<LineCmd> leaders;
    RenderTarget target;
    bool haveTarget = false;
    int samples = 1;

    // Per frame.
    int rw = 0, rh = 0, ss = 1;  // render size and supersampling factor
    Eigen::Matrix4d viewProjection;

    Impl(GlContext& c, const CanvasOptions& o) : context(c), options(o) {}

    /// Clip-space position of a world point with the frame's matrix.
    Vector4d clip(const Vector3d& p) const { return viewProjection * Vector4d(p.x(), p.y(), p.z(), 1.0); }
    /// Render-pixel position (x right, y down) and NDC depth of a clip-space point (w > 0).
    Vector3d screen(const Vector4d& c) const {
        return {(c.x() / c.w() + 1.0) * 0.5 * rw, (1.0 - c.y() / c.w()) * 0.5 * rh, c.z() / c.w()};
    }
    /// Clip-space vertex for a render-pixel position and NDC depth.
    void pixelVertex(Vertex& v, double x, double y, double z) const {
        set4(v.pos, 2.0 * x / rw - 1.0, 1.0 - 2.0 * y / rh, std::clamp(z, -1.0, 1.0), 1.0);
    }
    bool is3D() const { return camera.projection != Camera::Projection::TwoD; }

    /// Clips segment ab (clip space) to the near plane z >= -w; false if nothing is left.
    static bool clipNear(Vector4d& a, Vector4d& b) {
        const double da = a.z() + a.w(), db = b.z() + b.w();
        if (!(da >= 0) && !(db >= 0)) return false;  // also rejects NaN
        if (da < 0) a = a + (b - a) * (da / (da - db));
        if (db < 0) b = b + (a - b) * (db / (db - da));
        return std::isfinite(a.squaredNorm()) && std::isfinite(b.squaredNorm()) && a.w() > 0 && b.w() > 0;
    }

    /// Output-pixel position of a world point; false behind the eye.
    bool toPixels(const Vector3d& p, Vector2d& px) const {
        const Vector4d c = clip(p);
        if (!(c.w() > 0) || !(c.z() >= -c.w()) || !c.allFinite()) return false;
        px = screen(c).head<2>() / ss;
        return px.allFinite();
    }
    // readPixels(), in order: setFrameSize, prepareTarget, layoutTexts (places the labels),
    // buildFrame, renderPasses, readBack; layout() only the first and the third.
    void setFrameSize();
    void prepareTarget(GlContext::Impl& gl);
    FigureLayout layoutTexts();
    /// The notes (quantities, bodies, features, axes, series) as the picture shows them (canvas_notes.cpp).
    void recordNotes(FigureLayout& layout) const;
    FrameVertices buildFrame();
    void renderPasses(GlContext::Impl& gl, const FrameVertices& frame);
    Image readBack(FigureLayout layout);
    void buildMeshes(std::vector<Vertex>& opaque, std::vector<Vertex>& translucent);
    void addCapsule(std::vector<Vertex>& out, const Vector3d& a, const Vector3d& b, double halfW, double dash,
                    double phase, const Color& color);
    void buildOverlays(std::vector<Vertex>& out);  // lines, points, then the leader lines
    void buildLine(std::vector<Vertex>& out, const LineCmd& line);
    void buildPoint(std::vector<Vertex>& out, const PointCmd& point);
    void buildText(std::vector<Vertex>& out, std::vector<std::pair<GLuint, std::pair<int, int>>>& runs, int base);
};

}  // namespace cdlab::render
