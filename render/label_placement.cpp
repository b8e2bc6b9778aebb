#include "render/label_placement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace cdlab::render {

using Eigen::Vector2d;

double pointSegmentDistance(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
    const Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (a + t * ab - p).norm();
}

namespace {

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
    for (int k = 0; k < 32; ++k) {
        const double angle = k * M_PI / 16;
        dirs.emplace_back(std::cos(angle), std::sin(angle));
    }
    std::stable_sort(dirs.begin(), dirs.end(),
                     [&](const Vector2d& x, const Vector2d& y) { return x.dot(preferred) > y.dot(preferred); });
    dirs.insert(dirs.begin(), preferred);
    return dirs;
}

// Do segments ab and cd cross properly (each one's ends strictly on both sides of the other)? A
// leader starts on its anchor, often a vertex: the edges meeting there do not count.
bool segmentsCross(const Vector2d& a, const Vector2d& b, const Vector2d& c, const Vector2d& d) {
    const auto cross = [](const Vector2d& u, const Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
    const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
    const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
    return d1 * d2 < 0 && d3 * d4 < 0;
}

}  // namespace

double segmentBoxDistance(const Vector2d& a, const Vector2d& b, const Box& box) {
    if (segmentHitsBox(a, b, box)) return 0.0;
    double d = std::min(box.distanceTo(a), box.distanceTo(b));
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
    // Each stroke's bounding box, for exact early rejections: a stroke whose box is at least r + 1e-6
    // px from a candidate (on one axis) is farther than r from it, whatever the rounding of the
    // exact distance (segmentBoxDistance), so skipping it changes no decision. A dense drawing (a
    // tessellated disk: ~1000 strokes, ~500 candidates a label) spent most of its time there.
    const auto segmentBox = [](const Vector2d& a, const Vector2d& b) {
        return Box{std::min(a.x(), b.x()), std::min(a.y(), b.y()), std::max(a.x(), b.x()), std::max(a.y(), b.y())};
    };
    std::vector<Box> lineBoxes;
    lineBoxes.reserve(obstacles.lines.size());
    for (const PlacementObstacles::Line& l : obstacles.lines) lineBoxes.push_back(segmentBox(l.a, l.b));
    const auto apart = [](const Box& p, const Box& q, double r) {
        return std::max({p.x0 - q.x1, q.x0 - p.x1, p.y0 - q.y1, q.y0 - p.y1}) >= r + 1e-6;
    };
    const auto offLines = [&](const Box& b, bool thinToo) {
        for (size_t i = 0; i < obstacles.lines.size(); ++i) {
            const PlacementObstacles::Line& l = obstacles.lines[i];
            if ((thinToo || !l.thin) && (l.owner == 0 || l.owner != request.names) &&
                !apart(lineBoxes[i], b, l.halfWidth + 1.0) && segmentBoxDistance(l.a, l.b, b) < l.halfWidth + 1.0)
                return false;
        }
        return true;
    };
    // No preferred side (a name that belongs on its point, such as a body's): on the point if free.
    if (!(request.preferred.norm() > 1e-9)) {
        const Box centered{request.anchor.x() - 0.5 * request.size.x(), request.anchor.y() - 0.5 * request.size.y(),
                           request.anchor.x() + 0.5 * request.size.x(), request.anchor.y() + 0.5 * request.size.y()};
        if (free(centered) && offLines(centered, true)) return {true, centered, false};
    }
    const auto ambiguous = [&](const Box& b) {
        const double own = b.distanceTo(request.anchor);
        for (const Vector2d& a : obstacles.anchors)
            if ((a - request.anchor).norm() >= 1.0 && b.distanceTo(a) + 0.5 < own) return true;
        return false;
    };
    const std::vector<Vector2d> dirs = candidateDirections(request.preferred);
    // What a leader costs beyond its length (figure reviews of 2026-11-29): 8 for each stroke it
    // crosses ("its leader lost among edges"); 80 for running along a stroke or carrying one on
    // past the anchor (an arrow's shaft, a body's edge: it reads as part of it, or as naming that
    // stroke's far end); 500 for passing through another label or marker (it reads as naming it).
    const auto leaderCost = [&](const Box& b) {
        const Vector2d near = b.nearest(request.anchor);
        const Vector2d leader = near - request.anchor;
        const double length = leader.norm();
        if (length < 1) return 0.0;
        const Vector2d u = leader / length;
        double cost = 0;
        for (const Box& o : obstacles.boxes) {
            if (o.contains(request.anchor)) continue;  // its own marker
            double t0, t1;
            if (o.clip(request.anchor, near, t0, t1) && (t1 - t0) * length > 1.0) cost += 500;
        }
        // The leader's box grown by the largest reach tested below (5 px from an end, halfWidth + 4
        // along a stroke): a stroke whose box is beyond it adds nothing but a crossing, which needs
        // the boxes to overlap.
        const Box leaderBox = segmentBox(request.anchor, near);
        for (size_t i = 0; i < obstacles.lines.size(); ++i) {
            const PlacementObstacles::Line& l = obstacles.lines[i];
            if (apart(lineBoxes[i], leaderBox, std::max(5.0, l.halfWidth + 4.0))) continue;
            // 30 for passing by or ending at another vertex (a stroke's end away from the anchor,
            // its own body's too): the label reads as naming that corner (figure review: "V1 (A)"
            // led to the icosahedron's silhouette vertex, "s_B(−n)" to the box's hidden corner).
            for (const Vector2d& end : {l.a, l.b})
                if ((end - request.anchor).norm() > 6.0 && pointSegmentDistance(end, request.anchor, near) < 5.0) {
                    cost += 30;
                    break;
                }
            if (l.owner != 0 && l.owner == request.names) continue;
            if (segmentsCross(request.anchor, near, l.a, l.b)) cost += 8;
            const Vector2d ld = l.b - l.a;
            if (!(ld.norm() > 1)) continue;
            if (std::abs(u.dot(ld.normalized())) < 0.94) continue;  // within 20 degrees of parallel
            int along = 0;
            for (double t : {0.2, 0.35, 0.5, 0.65, 0.8})
                if (pointSegmentDistance(request.anchor + t * leader, l.a, l.b) < l.halfWidth + 4.0) ++along;
            const bool fromEnd = (l.a - request.anchor).norm() < 5.0 || (l.b - request.anchor).norm() < 5.0;
            if (along >= 3 || fromEnd) cost += 80;
        }
        return cost;
    };
    // Rings: next to the anchor, then farther out with a leader line back to it; the last ten
    // reach past a dense drawing's outline (a vertex inside a wireframe has no free spot near it).
    constexpr int kRings = 15;
    const auto ringDistance = [&](int ring) {
        constexpr double near[5] = {1.0, 1.75, 2.5, 3.5, 4.5};
        constexpr double far[10] = {15, 30, 45, 60, 80, 100, 125, 150, 175, 200};
        if (ring < 5) return request.gap * near[ring] + (ring ? 8.0 : 0.0);
        return request.gap * near[4] + 8.0 + far[ring - 5];
    };
    Placement best;
    double bestCost = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring < kRings; ++ring)
        for (const Vector2d& d : dirs) {
            const Box b = boxAt(request.anchor, request.size, d, ringDistance(ring));
            if (!free(b)) continue;
            // Crossing a thick stroke is worst, then being nearer another point than its own (it
            // misleads), then a leader through another label (leaderCost), then crossing a thin
            // stroke: each of these outweighs any clean spot's leader, which costs 2 for each ring
            // beyond the second and leaderCost, so of the clean spots the nearest, most direct wins.
            const double crossing = offLines(b, false) ? (offLines(b, true) ? 0 : 400) : 1000;
            const double cost = crossing + (ambiguous(b) ? 700 : 0) + 2.0 * std::max(0, ring - 1) +
                                (ring > 0 ? leaderCost(b) : 0.0);
            if (cost == 0) return {true, b, ring > 0, 0.0};
            if (cost < bestCost) bestCost = cost, best = {true, b, ring > 0, cost};
        }
    return best;
}

}  // namespace cdlab::render
