#include "render/label_placement.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace cdlab::render {

namespace {

using Eigen::Vector2d;

double pointSegmentDistance(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
    const Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (a + t * ab - p).norm();
}

double pointBoxDistance(const Vector2d& p, const Box& b) {
    const double dx = std::max({b.x0 - p.x(), 0.0, p.x() - b.x1});
    const double dy = std::max({b.y0 - p.y(), 0.0, p.y() - b.y1});
    return std::hypot(dx, dy);
}

// Liang–Barsky: does segment ab enter the box?
bool segmentHitsBox(const Vector2d& a, const Vector2d& b, const Box& box) {
    double t0, t1;
    return box.clip(a, b, t0, t1);
}

// A box of `size` beside the anchor on the side `dir` (unit) points to, `gap` px away: centred
// on the anchor's row or column for a (nearly) axial direction, else with its nearest corner at
// the anchor (Imhof's corner positions), so a wide label never drifts far from its point.
Box boxAt(const Vector2d& anchor, const Vector2d& size, const Vector2d& dir, double gap) {
    const auto side = [](double d) { return d > 0.2 ? 1.0 : d < -0.2 ? -1.0 : 0.0; };
    const Vector2d c = anchor + dir * gap + Vector2d(side(dir.x()) * 0.5 * size.x(), side(dir.y()) * 0.5 * size.y());
    return {c.x() - 0.5 * size.x(), c.y() - 0.5 * size.y(), c.x() + 0.5 * size.x(), c.y() + 0.5 * size.y()};
}

// The preferred direction, then sixteen directions by their angle from it (the eight compass
// points and the eight between them: a gap between two grid lines is often only on a diagonal).
std::vector<Vector2d> candidateDirections(Vector2d preferred) {
    if (!(preferred.norm() > 1e-9) || !preferred.allFinite()) preferred = Vector2d(1, -1);
    preferred.normalize();
    std::vector<Vector2d> dirs;
    for (int k = 0; k < 16; ++k) {
        const double angle = k * M_PI / 8;
        dirs.emplace_back(std::cos(angle), std::sin(angle));
    }
    std::stable_sort(dirs.begin(), dirs.end(),
                     [&](const Vector2d& x, const Vector2d& y) { return x.dot(preferred) > y.dot(preferred); });
    dirs.insert(dirs.begin(), preferred);
    return dirs;
}

}  // namespace

double segmentBoxDistance(const Vector2d& a, const Vector2d& b, const Box& box) {
    if (segmentHitsBox(a, b, box)) return 0.0;
    double d = std::min(pointBoxDistance(a, box), pointBoxDistance(b, box));
    const std::array<Vector2d, 4> corners = {Vector2d(box.x0, box.y0), Vector2d(box.x1, box.y0),
                                             Vector2d(box.x1, box.y1), Vector2d(box.x0, box.y1)};
    for (const Vector2d& c : corners) d = std::min(d, pointSegmentDistance(c, a, b));
    return d;
}

Placement placeLabel(const PlacementRequest& request, const PlacementObstacles& obstacles) {
    const Box inner{obstacles.panel.x0 + obstacles.margin, obstacles.panel.y0 + obstacles.margin,
                    obstacles.panel.x1 - obstacles.margin, obstacles.panel.y1 - obstacles.margin};
    const auto free = [&](const Box& b) {
        if (!inner.contains(b)) return false;
        for (const Box& o : obstacles.boxes)
            if (b.overlapArea(o) > 0) return false;
        return true;
    };
    const auto offLines = [&](const Box& b, bool thinToo) {
        for (const PlacementObstacles::Line& l : obstacles.lines)
            if ((thinToo || !l.thin) && (l.owner == 0 || l.owner != request.names) &&
                segmentBoxDistance(l.a, l.b, b) < l.halfWidth + 1.0)
                return false;
        return true;
    };
    // No preferred side (a name that belongs on its point, such as a body's): on the point if free.
    if (!(request.preferred.norm() > 1e-9)) {
        const Box centered{request.anchor.x() - 0.5 * request.size.x(), request.anchor.y() - 0.5 * request.size.y(),
                           request.anchor.x() + 0.5 * request.size.x(), request.anchor.y() + 0.5 * request.size.y()};
        if (free(centered) && offLines(centered, true)) return {true, centered, false};
    }
    const auto ambiguous = [&](const Box& b) {
        const double own = pointBoxDistance(request.anchor, b);
        for (const Vector2d& a : obstacles.anchors)
            if ((a - request.anchor).norm() >= 1.0 && pointBoxDistance(a, b) + 0.5 < own) return true;
        return false;
    };
    const std::vector<Vector2d> dirs = candidateDirections(request.preferred);
    // Rings: next to the anchor, then farther out (with a leader line back to the anchor).
    const double rings[5] = {1.0, 1.75, 2.5, 3.5, 4.5};
    Placement best;
    int bestCost = 1 << 30;
    for (int ring = 0; ring < 5; ++ring)
        for (const Vector2d& d : dirs) {
            const Box b = boxAt(request.anchor, request.size, d, request.gap * rings[ring] + (ring ? 8.0 : 0.0));
            if (!free(b)) continue;
            // Crossing a thick line is worst, then being nearer another point than its own (it
            // misleads), then crossing a thin line; each ring beyond the second costs 1, so a label
            // does not fly far off across a dense drawing to dodge one thin line (figure review of
            // 2026-11-29's re-render: "V0 (B)" 80 px from its point, its leader lost among edges).
            const int cost = (offLines(b, false) ? (offLines(b, true) ? 0 : 2) : 8) + (ambiguous(b) ? 9 : 0) +
                             std::max(0, ring - 1);
            if (cost == 0) return {true, b, ring > 0};
            if (cost < bestCost) bestCost = cost, best = {true, b, ring > 0};
        }
    return best;
}

}  // namespace cdlab::render
