// The legibility check of a figure's layout (render/figure_layout.h): what makes a frame unfit
// for a slide. Pure geometry on the recorded boxes; no pixels are read.
#pragma once

#include <string>
#include <vector>

#include "render/figure_layout.h"

namespace cdlab::render {

enum class LegibilityKind {
    LabelsOverlap,      // two labels' boxes overlap
    LabelsRunTogether,  // two labels on one line closer than a space: they read as one text
    LabelOnMarker,      // a label covers a marker it does not name (its point is elsewhere)
    LabelOutsidePanel,  // a label leaves its panel (the innermost one holding its anchor) or the image
    TextTooSmall,       // a line height under kMinLineHeightFraction of the image height
    Unplaced,           // the placement step found no free position (the label was not drawn)
};
const char* nameOf(LegibilityKind kind);

/// 1.5 % of the image height: 15 px on a 1024-px frame, about 11 pt on a projected slide.
constexpr double kMinLineHeightFraction = 0.015;
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
};

/// One line for a report: `rule: "text" detail`.
std::string describe(const LegibilityProblem& problem);

/// Every problem of a picture of width x height with this layout, worst first.
std::vector<LegibilityProblem> checkLegibility(const FigureLayout& layout, int width, int height);

}  // namespace cdlab::render
