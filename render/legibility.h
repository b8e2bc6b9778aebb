// The legibility check of a figure's layout (render/figure_layout.h): what makes a frame unfit
// for a slide: geometry on the recorded boxes (checkLegibility), and what the pixels show of the
// step's feature (checkFigure).
#pragma once

#include <string>
#include <vector>

#include "render/figure_layout.h"
#include "render/image.h"

namespace cdlab::render {

enum class LegibilityKind {
    LabelsOverlap,      // two labels' boxes overlap
    LabelsRunTogether,  // two labels on one line closer than a space: they read as one text
    LabelOnMarker,      // a label covers a marker it does not name (its point is elsewhere)
    LabelOutsidePanel,  // a label leaves its panel (the innermost one holding its anchor) or the image
    TextTooSmall,       // a font size under kMinLineHeightFraction of the image height
    Unplaced,           // the placement step found no free position (the label was not drawn)
    FontBelowTarget,    // a font size under kTargetFontFraction of the image height (issue 42)
    LabelOnStroke,      // a label's box crosses a drawn stroke other than its own leader line
                        // or the outline of the body it names
    LabelNearerOther,   // a label is nearer another label's point (in its panel) than its own
    QuantityTooSmall,   // a quantity the frame names (layout.quantities) drawn under kMinQuantityPx
                        // everywhere it is drawn (a zoomed inset that draws it larger is enough)
    BodyCutByPanel,     // a body (layout.bodies) reaches past the edge of its panel (the smallest
                        // holding its outline's centre) by more than kBodySlackPx
    SeparatedBodiesOverlap,  // two bodies the trace says are apart overlap on the picture by more
                             // than kBodySlackPx (a reader takes them for touching)
    FeatureEdgeOn,      // the feature a step changed seen edge-on: a face's normal, or an edge's
                        // direction, within acos(kEdgeOnFraction) of the view
    FeatureFromBehind,  // the feature a step changed is on the far side of its body (every face
                        // holding it turned away from the eye)
    HiddenFilled,       // a highlighted feature on the far side of its body drawn filled (hidden
                        // geometry is dashed or hollow)
    LogAxisWithoutValues,  // a log-scale axis with fewer than two numbers printed along it
    SeriesShareColour,     // two series or reference lines of one plot, named apart, in one colour
    StepFeatureFaded,      // the feature a step changed, facing the eye, does not show the colour
                           // it is named in (blended into the faces around it: issue 42 §3)
};
const char* nameOf(LegibilityKind kind);

/// The smallest font size that fails the gate, 1.5 % of the image height: 15 px on a 1024-px frame.
constexpr double kMinLineHeightFraction = 0.015;
/// The smallest font size the target asks for, 1.6 %: 16.4 px on a 1024-px frame, 12.3 px on
/// a 768-px one (about 12 pt on a projected slide).
constexpr double kTargetFontFraction = 0.016;
/// The shortest a named quantity (a gap, a depth) may be drawn, px: shorter, a reader cannot see it.
constexpr double kMinQuantityPx = 12.0;
/// How far (px) a body may reach past its panel's edge: anti-aliasing, not a cut.
constexpr double kBodySlackPx = 1.5;
/// A face seen at more than acos(0.26) = 75° from its normal shows under a quarter of its area; an
/// edge within 15° of the view direction shows under a quarter of its length: edge-on.
constexpr double kEdgeOnFraction = 0.26;
/// A log axis carries its values: at least this many numeric labels within kAxisValueReachPx of it.
constexpr int kMinLogAxisValues = 2;
constexpr double kAxisValueReachPx = 48.0;
/// Two colours whose channels all differ by at most this (of 255) read as one.
constexpr unsigned kSameColourDelta = 16;
/// A pixel within this (of 255, every channel) of a step feature's colour shows it. Measured on the
/// goldens: EPA's closest face at 0.8 alpha over the polytope was 44–127 off (olive), the walks'
/// faces at 0.55 alpha 53–122 off; drawn opaque or at 0.9 alpha every one passes.
constexpr unsigned kHighlightDelta = 32;
/// A stroke whose edge reaches less than this (px) into a label's box only grazes it.
constexpr double kStrokeGrazePx = 1.5;
/// Overlaps smaller than this (px²) are anti-aliasing contact, not overprinting.
constexpr double kOverlapSlackArea = 4.0;
/// Two labels side by side on one line need a gap of a quarter of their line height (a space in
/// DejaVu Sans is 0.32 em): closer, "E = 0.76" and "Jt = 1.2 s" read as one caption.
constexpr double kMinGapFraction = 0.25;

struct LegibilityProblem {
    LegibilityKind kind;
    std::string text;    // the label (first label, for an overlap)
    std::string detail;  // the other label, the marker, the panel, the size
    double severity;     // overlap area px², distance outside px, or px missing from the line height
    std::string other = "";  // LabelNearerOther: the label whose anchor it is nearer (placement retries it too)
};

/// One line for a report: `rule: "text" detail`.
std::string describe(const LegibilityProblem& problem);

/// Every problem of a picture of width x height with this layout, worst first.
std::vector<LegibilityProblem> checkLegibility(const FigureLayout& layout, int width, int height);

/// checkLegibility of the image's layout, and StepFeatureFaded from its pixels: at the samples of a
/// step's edge or filled face facing the eye (LayoutFeature::samples, less those under a label or a marker and,
/// for a face, under a stroke), at least half within kHighlightDelta of its colour.
std::vector<LegibilityProblem> checkFigure(const Image& image);

}  // namespace cdlab::render
