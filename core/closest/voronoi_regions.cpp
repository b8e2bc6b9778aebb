// Voronoi-region geometry of triangles and tetrahedra for drawing (Ericson §5.1.5, §5.1.6).
#include "core/closest/voronoi_regions.h"

#include <algorithm>
#include <limits>

#include "core/base/exact_predicates.h"

namespace cdlab {

std::vector<Vec3> clipConvexPolygon(const std::vector<Vec3>& polygon, const HalfSpace& h) {
    std::vector<Vec3> out;
    const std::size_t n = polygon.size();
    out.reserve(n + 1);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& p = polygon[i];
        const Vec3& q = polygon[(i + 1) % n];
        const double dp = h.normal.dot(p - h.point), dq = h.normal.dot(q - h.point);
        if (dp <= 0.0) out.push_back(p);
        // Strict sign change: the edge crosses the plane; the interpolation weight is in (0, 1).
        if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
    }
    return out;
}

namespace {

std::vector<Vec3> clipAll(std::vector<Vec3> polygon, std::initializer_list<HalfSpace> halfSpaces) {
    for (const HalfSpace& h : halfSpaces) polygon = clipConvexPolygon(polygon, h);
    return polygon;
}

}  // namespace

TriangleVoronoiDiagram triangleVoronoiRegions(const TriangleVoronoiInput& input) {
    TriangleVoronoiDiagram d;
    const Vec3 &a = input.triangle.a, &b = input.triangle.b, &c = input.triangle.c;
    if (!allFinite({a, b, c}) || exact::collinear(a, b, c)) return d;
    const Vec3 n = (b - a).cross(c - a);
    d.valid = true;
    d.normal = n.normalized();
    d.axisU = (b - a).normalized();
    d.axisV = d.normal.cross(d.axisU);

    // Clip rectangle: in-plane bounding box (coordinates along axisU, axisV from a) + margin.
    auto to2d = [&](const Vec3& x) { return Vec2(d.axisU.dot(x - a), d.axisV.dot(x - a)); };
    auto to3d = [&](const Vec2& uv) { return Vec3(a + uv.x() * d.axisU + uv.y() * d.axisV); };
    const Vec2 pa = to2d(a), pb = to2d(b), pc = to2d(c);
    const Vec2 lo = pa.cwiseMin(pb).cwiseMin(pc) - Vec2::Constant(input.margin);
    const Vec2 hi = pa.cwiseMax(pb).cwiseMax(pc) + Vec2::Constant(input.margin);
    d.rectangle = {to3d(lo), to3d(Vec2(hi.x(), lo.y())), to3d(hi), to3d(Vec2(lo.x(), hi.y()))};
    const std::vector<Vec3> rect(d.rectangle.begin(), d.rectangle.end());

    // In-plane outward edge normals: (b-a)×n points away from c, etc.
    const Vec3 outAB = (b - a).cross(d.normal).normalized();
    const Vec3 outBC = (c - b).cross(d.normal).normalized();
    const Vec3 outCA = (a - c).cross(d.normal).normalized();

    using R = TriangleRegion;
    auto set = [&](R region, std::vector<Vec3> polygon) {
        d.regions[static_cast<int>(region)] = {region, std::move(polygon)};
    };
    set(R::A, clipAll(rect, {{a, b - a}, {a, c - a}}));
    set(R::B, clipAll(rect, {{b, a - b}, {b, c - b}}));
    set(R::C, clipAll(rect, {{c, a - c}, {c, b - c}}));
    set(R::AB, clipAll(rect, {{a, a - b}, {b, b - a}, {a, -outAB}}));
    set(R::BC, clipAll(rect, {{b, b - c}, {c, c - b}, {b, -outBC}}));
    set(R::CA, clipAll(rect, {{c, c - a}, {a, a - c}, {c, -outCA}}));
    set(R::ABC, clipAll(rect, {{a, outAB}, {b, outBC}, {c, outCA}}));

    // Boundary planes. The in-plane boundary starts at `from` and runs along `along` to the
    // rectangle's edge (or to `to` for the edge-containing planes).
    auto rayToRectangle = [&](const Vec3& from, const Vec3& along) {
        const Vec2 o = to2d(from), dir(d.axisU.dot(along), d.axisV.dot(along));
        double t = std::numeric_limits<double>::infinity();
        for (int i = 0; i < 2; ++i) {
            if (dir[i] > 0.0) t = std::min(t, (hi[i] - o[i]) / dir[i]);
            if (dir[i] < 0.0) t = std::min(t, (lo[i] - o[i]) / dir[i]);
        }
        return Vec3(from + std::max(t, 0.0) * along);
    };
    const Vec3 up = input.height * d.normal;
    auto plane = [&](const Vec3& point, const Vec3& normal, R behind, R front, const Vec3& s0, const Vec3& s1) {
        return VoronoiBoundaryPlane{point, normal.normalized(), behind, front, {s0 - up, s1 - up, s1 + up, s0 + up}};
    };
    d.boundaries = {
        plane(a, b - a, R::A, R::AB, a, rayToRectangle(a, outAB)),
        plane(a, c - a, R::A, R::CA, a, rayToRectangle(a, outCA)),
        plane(b, a - b, R::B, R::AB, b, rayToRectangle(b, outAB)),
        plane(b, c - b, R::B, R::BC, b, rayToRectangle(b, outBC)),
        plane(c, b - c, R::C, R::BC, c, rayToRectangle(c, outBC)),
        plane(c, a - c, R::C, R::CA, c, rayToRectangle(c, outCA)),
        plane(a, outAB, R::ABC, R::AB, a, b),
        plane(b, outBC, R::ABC, R::BC, b, c),
        plane(c, outCA, R::ABC, R::CA, c, a),
    };
    return d;
}

TetrahedronVoronoiDiagram tetrahedronVoronoiRegions(const TetrahedronVoronoiInput& input) {
    TetrahedronVoronoiDiagram d;
    const Tetrahedron& t = input.tetrahedron;
    const Vec3 v[4] = {t.a, t.b, t.c, t.d};
    if (!allFinite({t.a, t.b, t.c, t.d}) || exact::orient3dSign(t.a, t.b, t.c, t.d) == 0) return d;
    d.valid = true;
    for (const Vec3& x : v) d.box.extend(x);
    d.box.min() -= Vec3::Constant(input.margin);
    d.box.max() += Vec3::Constant(input.margin);

    // Unit direction of the part of (z - x) orthogonal to edge xy: points from the edge toward z
    // within the plane x, y, z.
    auto towardThird = [&](int x, int y, int z) {
        const Vec3 e = (v[y] - v[x]).normalized();
        const Vec3 w = v[z] - v[x];
        return Vec3((w - w.dot(e) * e).normalized());
    };
    // Outward unit normal of face xyz (away from the opposite vertex w).
    auto outward = [&](int x, int y, int z, int w) {
        Vec3 n = (v[y] - v[x]).cross(v[z] - v[x]);
        if (n.dot(v[w] - v[x]) > 0.0) n = -n;
        return Vec3(n.normalized());
    };

    static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                         {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};

    for (int x = 0; x < 4; ++x) {
        auto& r = d.regions[x];
        r.region = static_cast<TetrahedronRegion>(x);
        for (int y = 0; y < 4; ++y) {
            if (y != x) r.halfSpaces.push_back({v[x], (v[y] - v[x]).normalized()});
        }
    }
    for (int e = 0; e < 6; ++e) {
        const int x = kEdges[e][0], y = kEdges[e][1], z = kEdges[e][2], w = kEdges[e][3];
        auto& r = d.regions[4 + e];
        r.region = static_cast<TetrahedronRegion>(4 + e);
        const Vec3 dir = (v[y] - v[x]).normalized();
        r.halfSpaces = {{v[x], -dir}, {v[y], dir}, {v[x], towardThird(x, y, z)}, {v[x], towardThird(x, y, w)}};
    }
    auto& inside = d.regions[14];
    inside.region = TetrahedronRegion::ABCD;
    for (int f = 0; f < 4; ++f) {
        const int x = kFaces[f][0], y = kFaces[f][1], z = kFaces[f][2], w = kFaces[f][3];
        auto& r = d.regions[10 + f];
        r.region = static_cast<TetrahedronRegion>(10 + f);
        const Vec3 n = outward(x, y, z, w);
        // Outside the face plane, inside the prism over the face (toward each edge's third vertex).
        r.halfSpaces = {
            {v[x], -n}, {v[x], -towardThird(x, y, z)}, {v[y], -towardThird(y, z, x)}, {v[z], -towardThird(z, x, y)}};
        inside.halfSpaces.push_back({v[x], n});
    }

    // Faces: a square on each bounding plane, large enough to cover the box, clipped by the box
    // and by the region's other half-spaces.
    const Vec3 center = d.box.center();
    const double radius = d.box.diagonal().norm();
    const std::initializer_list<HalfSpace> boxSides = {{d.box.max(), Vec3::UnitX()}, {d.box.min(), -Vec3::UnitX()},
                                                       {d.box.max(), Vec3::UnitY()}, {d.box.min(), -Vec3::UnitY()},
                                                       {d.box.max(), Vec3::UnitZ()}, {d.box.min(), -Vec3::UnitZ()}};
    for (auto& r : d.regions) {
        r.faces.resize(r.halfSpaces.size());
        for (std::size_t i = 0; i < r.halfSpaces.size(); ++i) {
            const HalfSpace& h = r.halfSpaces[i];
            const Vec3 origin = center - h.normal * h.normal.dot(center - h.point);
            const Vec3 e1 = h.normal.unitOrthogonal(), e2 = h.normal.cross(e1);
            std::vector<Vec3> polygon = {origin + radius * (-e1 - e2), origin + radius * (e1 - e2),
                                         origin + radius * (e1 + e2), origin + radius * (-e1 + e2)};
            polygon = clipAll(std::move(polygon), boxSides);
            for (std::size_t j = 0; j < r.halfSpaces.size() && !polygon.empty(); ++j) {
                if (j != i) polygon = clipConvexPolygon(polygon, r.halfSpaces[j]);
            }
            r.faces[i] = std::move(polygon);
        }
    }
    return d;
}

}  // namespace cdlab
