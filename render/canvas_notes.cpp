// What a Canvas records of its notes (noteQuantity, noteBody, noteFeature, noteAxis, noteSeries)
// as the picture shows them: lengths, outlines and views in output pixels, for the legibility
// check (render/legibility.h).
#include <algorithm>
#include <cmath>
#include <vector>

#include "render/canvas_internal.h"

namespace cdlab::render {

namespace {

// The convex hull of points (Andrew's monotone chain), duplicates and collinear points dropped.
std::vector<Vector2d> convexHull(std::vector<Vector2d> p) {
    std::sort(p.begin(), p.end(), [](const Vector2d& a, const Vector2d& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    if (p.size() < 3) return p;
    const auto turn = [](const Vector2d& o, const Vector2d& a, const Vector2d& b) {
        return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
    };
    std::vector<Vector2d> h;
    for (const Vector2d& q : p) {  // lower chain
        while (h.size() >= 2 && turn(h[h.size() - 2], h.back(), q) <= 0) h.pop_back();
        h.push_back(q);
    }
    const std::size_t lower = h.size() + 1;
    for (std::size_t i = p.size() - 1; i-- > 0;) {  // upper chain
        while (h.size() >= lower && turn(h[h.size() - 2], h.back(), p[i]) <= 0) h.pop_back();
        h.push_back(p[i]);
    }
    h.pop_back();  // the first point again
    return h;
}

unsigned rgbOf(const Color& c) {
    const auto byte = [](float v) { return unsigned(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
    return byte(c.r) << 16 | byte(c.g) << 8 | byte(c.b);
}

}  // namespace

void Canvas::Impl::recordNotes(FigureLayout& layout) const {
    for (const QuantityCmd& q : quantities) {
        Vector2d a, b;
        if (toPixels(q.p, a) && toPixels(q.q, b)) layout.quantities.push_back({q.name, (b - a).norm()});
    }
    for (const BodyCmd& body : bodies) {
        std::vector<Vector2d> projected;
        for (const Vector3d& p : body.points)
            if (Vector2d q; toPixels(p, q)) projected.push_back(q);
        if (!projected.empty())
            layout.bodies.push_back({body.name, convexHull(std::move(projected)), body.apartFrom});
    }
    for (const FeatureNote& f : features) {
        if (f.points.empty() || !is3D()) continue;  // a 2D figure shows every feature face-on
        Vector3d centre = Vector3d::Zero();
        for (const Vector3d& p : f.points) centre += p;
        centre /= double(f.points.size());
        Vector2d at;
        if (!toPixels(centre, at)) continue;
        const FeatureView seen = featureView(f.points, f.normals, camera.directionToEye(centre));
        LayoutFeature noted{f.name, std::min(int(f.points.size()) - 1, 2), seen.facing, seen.foreshortening,
                            f.filled, f.step, at};
        if (f.color.a > 0) {
            noted.rgb = int(rgbOf(f.color));
            std::vector<Vector3d> samples;  // where the picture shows it (LayoutFeature::samples)
            if (f.points.size() == 1) samples = {f.points[0]};
            else if (f.points.size() == 2)
                for (const double t : {0.3, 0.5, 0.7}) samples.push_back((1 - t) * f.points[0] + t * f.points[1]);
            else {
                samples.push_back(centre);
                for (const Vector3d& p : f.points) samples.push_back(0.5 * (centre + p));
            }
            for (const Vector3d& p : samples)  // only where this picture shows it (an inset cuts)
                if (Vector2d q; toPixels(p, q) && q.x() >= 0 && q.y() >= 0 && q.x() < options.width &&
                                q.y() < options.height)
                    noted.samples.push_back(q);
        }
        layout.features.push_back(std::move(noted));
    }
    for (const AxisCmd& a : axes)
        if (Vector2d p, q; toPixels(a.p, p) && toPixels(a.q, q)) layout.axes.push_back({p, q, a.log});
    for (const SeriesCmd& k : series)
        if (Vector2d at; toPixels(k.at, at)) layout.series.push_back({k.name, rgbOf(k.color), at});
}

}  // namespace cdlab::render
