// The one placement step every point label goes through (Canvas, for texts drawn with
// TextStyle::place): candidate positions around the anchor, the preferred side first, then the
// eight compass directions nearest to it, then the same farther out with a leader line. A
// candidate must stay inside the panel and off every other label and marker; the first one that
// also keeps off thick lines wins, else the first that only touches lines; else the label is not
// placed (the caller reports it instead of drawing it over something).
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
    };
    Box panel;  // the label must stay inside, `margin` px from the edge
    double margin = 2.0;
    std::vector<Box> boxes;   // other labels and markers
    std::vector<Line> lines;  // thick lines and arrows
};

struct PlacementRequest {
    Eigen::Vector2d anchor;     // the point the label names, px
    Eigen::Vector2d size;       // the text box, px
    Eigen::Vector2d preferred;  // preferred direction from the anchor (any length; zero: on the point, else up-right)
    double gap = 6.0;           // px between the anchor and the nearest edge of the box
};

struct Placement {
    bool placed = false;
    Box box;
    bool leader = false;  // moved away from its anchor: draw a leader line
};

Placement placeLabel(const PlacementRequest& request, const PlacementObstacles& obstacles);

/// Distance from a segment to a box, px (0 when they meet).
double segmentBoxDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Box& box);

}  // namespace cdlab::render
