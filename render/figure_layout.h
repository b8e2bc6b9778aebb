// Where a figure's text and markers are, in pixels of the picture (origin top-left): what the
// legibility check (render/legibility.h) reads and what manifest.json records for every frame.
// A Canvas fills it in readPixels(); blit / stackVertically / downsample carry it along, so a
// composed frame knows every label of every panel pasted into it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace cdlab::render {

/// Axis-aligned pixel rectangle [x0, x1] x [y0, y1].
struct Box {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    double width() const { return x1 - x0; }
    double height() const { return y1 - y0; }
    Eigen::Vector2d center() const { return {0.5 * (x0 + x1), 0.5 * (y0 + y1)}; }
    /// Area of the intersection (0 when they only touch).
    double overlapArea(const Box& o) const;
    /// True when `o` lies inside this box, up to `slack` pixels on each side.
    bool contains(const Box& o, double slack = 0) const;
    bool contains(const Eigen::Vector2d& p) const { return p.x() >= x0 && p.x() <= x1 && p.y() >= y0 && p.y() <= y1; }
    Box translated(double dx, double dy) const { return {x0 + dx, y0 + dy, x1 + dx, y1 + dy}; }
    Box scaled(double s) const { return {x0 * s, y0 * s, x1 * s, y1 * s}; }
    /// The box's point nearest to p (p itself inside): where a leader line from p meets the box.
    Eigen::Vector2d nearest(const Eigen::Vector2d& p) const;
    /// Distance from p to the box (0 inside).
    double distanceTo(const Eigen::Vector2d& p) const;
    /// Segment ab clipped to the box (Liang–Barsky): its parameters [t0, t1] along ab inside, or
    /// false when no part of it is inside (a zero-length segment: whether its point is).
    bool clip(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double& t0, double& t1) const;
};

/// A text as drawn: its box spans the font's line height (ascent to descent) of every line and
/// the text's advance width; `anchor` is the point it names (null for titles and captions).
struct LayoutLabel {
    std::string text;
    Box box;
    std::optional<Eigen::Vector2d> anchor;
    double lineHeight = 0;  // the font size, px: one line's ascent + descent (manifest: size_px)
};

/// A drawn point marker (its disc's bounding box); `label` indexes the label that names it, or -1.
struct LayoutMarker {
    Box box;
    int label = -1;
};

/// A drawn stroke: a line, one segment of a polyline or an outline, an arrow's shaft (head
/// included in its length), a plot's axis, grid line or series segment, from `a` to `b` with its
/// pixel `width`. `leaderOf` indexes the label whose leader line it is (-1: none): the one label
/// allowed to touch it.
struct LayoutStroke {
    Eigen::Vector2d a{0, 0}, b{0, 0};
    double width = 0;
    int leaderOf = -1;
    int outlineOf = -1;  ///< the label naming the body this stroke outlines (TextStyle::names), or -1
};

/// A quantity the frame names (a gap, a depth, the change from the previous step) and its drawn
/// length in pixels; the same name drawn again in a zoomed inset counts at its longest
/// (render/legibility.h: QuantityTooSmall).
struct LayoutQuantity {
    std::string name;
    double px = 0;
};

/// A body as the frame draws it (Canvas::noteBody): the convex hull of its projected points, px
/// (render/legibility.h: BodyCutByPanel). `apartFrom` names the body the trace says it is
/// separated from ("" none): their outlines must not overlap (SeparatedBodiesOverlap).
struct LayoutBody {
    std::string name;
    std::vector<Eigen::Vector2d> outline;
    std::string apartFrom;
};

/// A feature a frame highlights (Canvas::noteFeature) and how its camera sees it
/// (FeatureEdgeOn, FeatureFromBehind, HiddenFilled).
struct LayoutFeature {
    std::string name;
    int dimension = 0;  ///< 0 vertex, 1 edge, 2 face
    /// The largest cosine between the outward normal of a face holding the feature and the direction
    /// to the eye: below 0, every face holding it is turned away (the feature is seen from behind).
    double facing = 1;
    /// How much of it the view shows: a face's |cos| between its normal and the view, an edge's
    /// |sin| between its direction and the view; 1 for a vertex. Near 0: edge-on (or end-on).
    double foreshortening = 1;
    bool filled = false;  ///< drawn as a filled region
    bool step = false;    ///< what the frame's step changed: the frame is built around it
    Eigen::Vector2d at{0, 0};  ///< its centre on the picture, px (finds its panel)
    /// The colour it is drawn in, 0xRRGGBB (-1: not judged), and the points of the picture that
    /// show it: a face's centre and halfway to each corner, an edge's 0.3 / 0.5 / 0.7 points, a
    /// vertex (StepFeatureFaded: most of them, where no label or marker covers them, in that colour).
    int rgb = -1;
    std::vector<Eigen::Vector2d> samples{};
};

/// An axis of a plot, from `a` to `b` on the picture: a log axis needs its values printed
/// (LogAxisWithoutValues: at least two numeric labels beside it).
struct LayoutAxis {
    Eigen::Vector2d a{0, 0}, b{0, 0};
    bool log = false;
};

/// A series or reference line of a plot as its legend names it, with its colour (0xRRGGBB) and a
/// point of it (finds its panel): two with one colour read as one thing (SeriesShareColour).
struct LayoutSeries {
    std::string name;
    unsigned rgb = 0;
    Eigen::Vector2d at{0, 0};
};

struct FigureLayout {
    std::vector<Box> panels;  // the canvases a frame was composed from, outermost first
    std::vector<LayoutLabel> labels;
    std::vector<LayoutMarker> markers;
    std::vector<LayoutStroke> strokes;
    std::vector<LayoutQuantity> quantities;
    std::vector<LayoutBody> bodies;
    std::vector<LayoutFeature> features;
    std::vector<LayoutAxis> axes;
    std::vector<LayoutSeries> series;
    /// Labels the placement step could not put anywhere free: reported here, not drawn.
    std::vector<std::string> unplaced;

    /// Adds `other`, moved by (dx, dy) (marker label indices follow their labels).
    void append(const FigureLayout& other, double dx, double dy);
    /// An opaque picture pasted over `area` hides what was there: strokes keep only their parts
    /// outside it; labels and markers wholly inside are dropped (indices into labels follow).
    /// Call before appending the pasted picture's own layout (readPixelsZoomed, demos/draw/zoom_inset.cpp).
    void cover(const Box& area);
    /// Every coordinate times s (a picture resized by s).
    FigureLayout scaled(double s) const;
};

}  // namespace cdlab::render
