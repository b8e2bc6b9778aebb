// The one placement step every point label goes through (Canvas, for texts drawn with
// TextStyle::place): candidate positions around the anchor, the preferred side first, then 32
// directions by their angle from it, then the same farther out (up to 200 px past the nearest
// rings) with a leader line. A candidate must stay inside the panel and off every other label and
// marker. Costs rank the rest: crossing a thick line worst, then lying nearer another anchor than
// its own, then a leader through another label, then crossing a thin line (the rules LabelOnStroke
// and LabelNearerOther of render/legibility.h), each above any clean spot's leader: its length,
// the strokes it crosses, running along a stroke or on from one, passing another vertex
// (tests/render/legibility_test.cpp, "a leader neither runs along..."). The first candidate of
// cost 0 wins, else the least (Placement::cost says what it weighed); a label with no candidate at
// all is not placed (the caller reports it instead of drawing it over something).
// Imhof, "Positioning names on maps" (1975) ranks the positions around a point the same way.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "render/figure_layout.h"

namespace cdlab::render {

struct PlacementObstacles {
    struct Line {
        Eigen::Vector2d a, b;
        double halfWidth;
        bool thin = false;  // below 3 px: avoided when possible, crossed when not
        int owner = 0;      // Canvas::setStrokeOwner (0: none)
    };
    Box panel;  // the label must stay inside, `margin` px from the edge
    double margin = 2.0;
    std::vector<Box> boxes;   // other labels and markers
    std::vector<Line> lines;  // every stroke drawn (lines, arrows, outlines)
    std::vector<Eigen::Vector2d> anchors;  // every label's anchor (a candidate nearer another one than
                                           // its own is avoided: LabelNearerOther)
};

struct PlacementRequest {
    Eigen::Vector2d anchor;     // the point the label names, px
    Eigen::Vector2d size;       // the text box, px
    Eigen::Vector2d preferred;  // preferred direction from the anchor (any length; zero: on the point, else up-right)
    double gap = 6.0;           // px between the anchor and the nearest edge of the box
    int names = 0;              // the owner of the strokes it may cross (its body's outline; 0: none)
};

struct Placement {
    bool placed = false;
    Box box;
    bool leader = false;  // moved away from its anchor: draw a leader line
    double cost = 0;      // 0: clean; else what placeLabel weighed against it (crossings, ambiguity, leader)
};

Placement placeLabel(const PlacementRequest& request, const PlacementObstacles& obstacles);

/// Distance from p to segment ab, px.
double pointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);
/// Distance from a segment to a box, px (0 when they meet).
double segmentBoxDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Box& box);

}  // namespace cdlab::render
