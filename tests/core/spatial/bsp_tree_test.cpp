// Solid-leaf BSP tree: point classification and segment queries against independent oracles
// (face planes for convex meshes, long-double winding number and ray-triangle tests for any
// closed mesh), area conservation of split polygons, degenerate input.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/spatial/bsp_tree.h"

using namespace cdlab;

namespace {

using LVec = Eigen::Matrix<long double, 3, 1>;
LVec L(const Vec3& v) { return v.cast<long double>(); }

std::vector<BspPolygon> transformed(std::vector<BspPolygon> polys, double scale, const Vec3& offset, const Quat& q) {
    for (BspPolygon& p : polys)
        for (Vec3& v : p.vertices) v = q * (scale * v) + offset;
    return polys;
}

// Unit cube [-1, 1]^3, quads counter-clockwise from outside.
std::vector<BspPolygon> cube() {
    std::vector<BspPolygon> out;
    for (int axis = 0; axis < 3; ++axis)
        for (double s : {-1.0, 1.0}) {
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            std::vector<Vec3> q;
            const double cu[4] = {-1, 1, 1, -1}, cw[4] = {-1, -1, 1, 1};
            for (int k = 0; k < 4; ++k) {
                Vec3 v;
                v[axis] = s;
                v[u] = cu[k];
                v[w] = cw[k];
                q.push_back(v);
            }
            if (s < 0) std::reverse(q.begin(), q.end());
            out.push_back({q});
        }
    return out;
}

// L-shaped prism: the L {[0,2]x[0,1]} u {[0,1]x[1,2]} extruded over z in [0, 1]; the L caps as
// two rectangles each (coplanar polygons with a T-junction).
std::vector<BspPolygon> lShape() {
    const std::vector<Vec2> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};  // counter-clockwise
    std::vector<BspPolygon> out;
    for (std::size_t i = 0; i < l.size(); ++i) {
        const Vec2 a = l[i], b = l[(i + 1) % l.size()];
        out.push_back({{Vec3(a.x(), a.y(), 0), Vec3(b.x(), b.y(), 0), Vec3(b.x(), b.y(), 1), Vec3(a.x(), a.y(), 1)}});
    }
    auto rect = [&](double x0, double y0, double x1, double y1, double z, bool up) {
        std::vector<Vec3> r = {Vec3(x0, y0, z), Vec3(x1, y0, z), Vec3(x1, y1, z), Vec3(x0, y1, z)};
        if (!up) std::reverse(r.begin(), r.end());
        out.push_back({r});
    };
    rect(0, 0, 2, 1, 1, true);
    rect(0, 1, 1, 2, 1, true);
    rect(0, 0, 2, 1, 0, false);
    rect(0, 1, 1, 2, 0, false);
    return out;
}

// Torus (major radius R around z, minor r) as triangles, outward normals.
std::vector<BspPolygon> torus(double R, double r, int nu, int nv) {
    auto at = [&](int i, int j) {
        const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
        return Vec3((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    };
    std::vector<BspPolygon> out;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const Vec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            out.push_back({{a, b, c}});
            out.push_back({{a, c, d}});
        }
    return out;
}

// ---- oracles (long double, independent of the BSP code) ----

// Generalized winding number of a closed polygon mesh at p (solid angles of fan triangles,
// van Oosterom & Strackee 1983): 1 inside, 0 outside.
long double windingNumber(const std::vector<BspPolygon>& polys, const Vec3& p) {
    long double total = 0;
    for (const BspPolygon& poly : polys)
        for (std::size_t k = 1; k + 1 < poly.vertices.size(); ++k) {
            const LVec a = L(poly.vertices[0]) - L(p), b = L(poly.vertices[k]) - L(p),
                       c = L(poly.vertices[k + 1]) - L(p);
            const long double la = a.norm(), lb = b.norm(), lc = c.norm();
            const long double num = a.dot(b.cross(c));
            const long double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
            total += 2 * std::atan2(num, den);
        }
    return total / (4 * static_cast<long double>(M_PI));
}

// Distance from p to the mesh surface (long double, point-triangle by dense-enough exact
// formula: min over fan triangles of the distance to the triangle's plane region / edges).
long double distanceToTriangle(const LVec& p, const LVec& a, const LVec& b, const LVec& c) {
    const LVec n = (b - a).cross(c - a);
    const long double nn = n.squaredNorm();
    // Inside the prism over the triangle: plane distance.
    const LVec q = p - n * (n.dot(p - a) / nn);
    const long double w0 = (b - q).cross(c - q).dot(n), w1 = (c - q).cross(a - q).dot(n),
                      w2 = (a - q).cross(b - q).dot(n);
    if (w0 >= 0 && w1 >= 0 && w2 >= 0) return (p - q).norm();
    auto seg = [&](const LVec& s, const LVec& t) {
        const LVec d = t - s;
        long double u = d.dot(p - s) / d.squaredNorm();
        u = std::clamp(u, (long double)0, (long double)1);
        return (p - (s + u * d)).norm();
    };
    return std::min({seg(a, b), seg(b, c), seg(c, a)});
}
long double distanceToMesh(const std::vector<BspPolygon>& polys, const Vec3& p) {
    long double best = INFINITY;
    for (const BspPolygon& poly : polys)
        for (std::size_t k = 1; k + 1 < poly.vertices.size(); ++k)
            best = std::min(
                best, distanceToTriangle(L(p), L(poly.vertices[0]), L(poly.vertices[k]), L(poly.vertices[k + 1])));
    return best;
}

// First parameter t in [0, 1] where segment a -> b meets a mesh triangle (Möller-Trumbore in
// long double); -1 if none.
long double firstMeshHit(const std::vector<BspPolygon>& polys, const Vec3& a, const Vec3& b) {
    const LVec o = L(a), d = L(b) - L(a);
    long double best = -1;
    for (const BspPolygon& poly : polys)
        for (std::size_t k = 1; k + 1 < poly.vertices.size(); ++k) {
            const LVec v0 = L(poly.vertices[0]), e1 = L(poly.vertices[k]) - v0, e2 = L(poly.vertices[k + 1]) - v0;
            const LVec h = d.cross(e2);
            const long double det = e1.dot(h);
            if (std::abs(det) < 1e-30L) continue;
            const LVec s = o - v0;
            const long double u = s.dot(h) / det;
            if (u < 0 || u > 1) continue;
            const LVec q = s.cross(e1);
            const long double v = d.dot(q) / det;
            if (v < 0 || u + v > 1) continue;
            const long double t = e2.dot(q) / det;
            if (t >= 0 && t <= 1 && (best < 0 || t < best)) best = t;
        }
    return best;
}

long double polygonArea(const std::vector<Vec3>& v) {
    LVec n = LVec::Zero();
    for (std::size_t k = 1; k + 1 < v.size(); ++k) n += (L(v[k]) - L(v[0])).cross(L(v[k + 1]) - L(v[0]));
    return n.norm() / 2;
}

// Random points in the box around the mesh, at least `margin` from its surface.
std::vector<Vec3> samplePoints(const std::vector<BspPolygon>& polys, std::mt19937& rng, int count, double margin) {
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    for (const BspPolygon& p : polys)
        for (const Vec3& v : p.vertices) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
    const Vec3 pad = 0.2 * (hi - lo);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec3> out;
    while (int(out.size()) < count) {
        const Vec3 p = lo - pad + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(hi - lo + 2 * pad);
        if (distanceToMesh(polys, p) > margin) out.push_back(p);
    }
    return out;
}

// Classification and segment queries vs the winding-number / ray-triangle oracles.
void checkMesh(const std::vector<BspPolygon>& polys, std::mt19937& rng, double margin, const BspOptions& options = {}) {
    BspTree tree;
    BspTrace trace;
    tree.build(polys, options, &trace);
    REQUIRE(tree.status() == BspStatus::Ok);
    const std::vector<Vec3> pts = samplePoints(polys, rng, 200, margin);
    int inside = 0;
    for (const Vec3& p : pts) {
        const long double w = windingNumber(polys, p);
        REQUIRE((std::abs(w) < 1e-6L || std::abs(w - 1) < 1e-6L));  // closed, outward-oriented mesh
        const BspPointClass want = w > 0.5L ? BspPointClass::Inside : BspPointClass::Outside;
        inside += want == BspPointClass::Inside;
        CHECK(tree.classifyPoint(p) == want);
    }
    CHECK(inside > 0);
    CHECK(inside < int(pts.size()));
    // Segments between sample points: first solid point vs first mesh crossing (or 0 from inside).
    double size = 0, maxAbs = 0;  // mesh size; largest coordinate (vertices are rounded to its ulp)
    for (const BspPolygon& p : polys)
        for (const Vec3& v : p.vertices) {
            size = std::max(size, (v - polys[0].vertices[0]).norm());
            maxAbs = std::max(maxAbs, v.cwiseAbs().maxCoeff());
        }
    const long double rounding = 1e-15L * maxAbs;  // a few ulps of the coordinates
    for (std::size_t k = 0; k + 1 < pts.size(); k += 2) {
        const Vec3 a = pts[k], b = pts[k + 1];
        const BspRayResult r = tree.segmentQuery({a, b});
        if (tree.classifyPoint(a) == BspPointClass::Inside) {
            CHECK(r.hit);
            CHECK(r.t == 0.0);
            CHECK(r.startsInside);
            continue;
        }
        const long double t = firstMeshHit(polys, a, b);
        CHECK(r.hit == (t >= 0));
        if (r.hit && t >= 0) CHECK(std::abs((long double)r.t - t) * (b - a).norm() < 1e-7L * size);
    }
    // Split fragments keep the area and lie on their polygon's plane.
    long double inputArea = 0, fragmentArea = 0;
    for (const BspPolygon& p : polys) inputArea += polygonArea(p.vertices);
    for (const BspFragment& f : tree.fragments()) {
        fragmentArea += polygonArea(f.vertices);
        const std::vector<Vec3>& src = polys[std::size_t(f.source)].vertices;
        const LVec n = (L(src[1]) - L(src[0])).cross(L(src[2]) - L(src[0])).normalized();
        for (const Vec3& v : f.vertices) CHECK(std::abs(n.dot(L(v) - L(src[0]))) <= 1e-9L * size + rounding);
    }
    CHECK(std::abs(fragmentArea - inputArea) <= 1e-12L * inputArea + rounding * size * tree.stats().fragmentCount);
    // Trace bookkeeping: one step per inner node; every fragment reaching a node is accounted for.
    CHECK(int(trace.steps.size()) == tree.stats().innerCount);
    int splits = 0;
    for (const BspSplitStep& s : trace.steps) {
        CHECK(s.front + s.back + s.coplanar + s.straddling == s.polygons);
        splits += s.straddling;
    }
    CHECK(splits == tree.stats().splits);
}

}  // namespace

TEST_SUITE("bsp_tree") {
    TEST_CASE("convex cube: face-plane oracle, every placement and scale") {
        std::mt19937 rng(1);
        const Quat q = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
        for (double scale : {1e-3, 1.0, 1e3})
            for (double offset : {0.0, 1e4, 1e6}) {
                const std::vector<BspPolygon> polys =
                    transformed(cube(), scale, Vec3(offset, -2 * offset, 0.5 * offset), q);
                BspTree tree;
                tree.build(polys);
                CHECK(tree.stats().splits == 0);
                CHECK(tree.stats().innerCount == 6);
                std::uniform_real_distribution<double> u(-2.0, 2.0);
                for (int k = 0; k < 300; ++k) {
                    const Vec3 local(u(rng), u(rng), u(rng));
                    const double m = local.cwiseAbs().maxCoeff();
                    if (std::abs(m - 1.0) < 0.01) continue;  // margin from the surface
                    const Vec3 p = q * (scale * local) + Vec3(offset, -2 * offset, 0.5 * offset);
                    // Oracle: inside iff behind every face plane (long double, from the mesh's vertices).
                    bool in = true;
                    for (const BspPolygon& f : polys) {
                        const LVec n = (L(f.vertices[1]) - L(f.vertices[0])).cross(L(f.vertices[2]) - L(f.vertices[0]));
                        in = in && n.dot(L(p) - L(f.vertices[0])) < 0;
                    }
                    CHECK(tree.classifyPoint(p) == (in ? BspPointClass::Inside : BspPointClass::Outside));
                }
                // Points on a face and on an edge are on the boundary.
                CHECK(tree.classifyPoint(q * (scale * Vec3(1, 0.3, -0.2)) + Vec3(offset, -2 * offset, 0.5 * offset)) ==
                      BspPointClass::OnBoundary);
                CHECK(tree.classifyPoint(q * (scale * Vec3(1, 1, 0.5)) + Vec3(offset, -2 * offset, 0.5 * offset)) ==
                      BspPointClass::OnBoundary);
            }
        checkMesh(cube(), rng, 0.01);
    }

    TEST_CASE("vertex orderings: cyclic shifts change nothing, reversal gives the complement") {
        std::mt19937 rng(2);
        const std::vector<BspPolygon> base = lShape();
        for (int shift = 1; shift < 4; ++shift) {
            std::vector<BspPolygon> shifted = base;
            for (BspPolygon& p : shifted) std::rotate(p.vertices.begin(), p.vertices.begin() + shift, p.vertices.end());
            checkMesh(shifted, rng, 0.02);
        }
        std::vector<BspPolygon> reversed = base;
        for (BspPolygon& p : reversed) std::reverse(p.vertices.begin(), p.vertices.end());
        BspTree a, b;
        a.build(base);
        b.build(reversed);
        for (const Vec3& p : samplePoints(base, rng, 200, 0.02)) {
            const BspPointClass ca = a.classifyPoint(p), cb = b.classifyPoint(p);
            CHECK(ca != BspPointClass::OnBoundary);
            CHECK(cb == (ca == BspPointClass::Inside ? BspPointClass::Outside : BspPointClass::Inside));
        }
    }

    TEST_CASE("non-convex L-shaped prism: winding number, ray-triangle oracle, areas, offsets and scales") {
        std::mt19937 rng(3);
        const Quat q = Quat(Eigen::AngleAxisd(0.4, Vec3(-1, 2, 0.5).normalized()));
        for (double scale : {1e-3, 1.0, 1e3})
            for (double offset : {0.0, 1e6})
                checkMesh(transformed(lShape(), scale, Vec3::Constant(offset), q), rng, 0.02 * scale);
    }

    TEST_CASE("non-convex torus (320 triangles): classification, segments, split areas") {
        std::mt19937 rng(4);
        const std::vector<BspPolygon> t = torus(2.0, 0.7, 16, 10);
        checkMesh(t, rng, 0.02);
        BspOptions balanced;
        balanced.splitWeight = 0.2;  // favour balance over fewer splits
        balanced.maxCandidates = 16;
        checkMesh(t, rng, 0.02, balanced);
        checkMesh(transformed(t, 10.0, Vec3(1e4, 1e4, -1e4), Quat::Identity()), rng, 0.2);
        BspTree tree;
        tree.build(t);
        MESSAGE("torus: nodes " << tree.stats().nodeCount << ", depth " << tree.stats().depth << ", splits "
                                << tree.stats().splits << ", fragments " << tree.stats().fragmentCount);
    }

    TEST_CASE("split weight trades splits against balance") {
        const std::vector<BspPolygon> t = torus(2.0, 0.7, 12, 8);
        BspTree fewSplits, balanced;
        BspOptions a, b;
        a.splitWeight = 1.0;
        b.splitWeight = 0.0;
        fewSplits.build(t, a);
        balanced.build(t, b);
        CHECK(fewSplits.stats().splits < balanced.stats().splits);
        CHECK(balanced.stats().depth < fewSplits.stats().depth);
    }

    TEST_CASE("degenerate input: empty, NaN, zero-area and short polygons, duplicates, coplanar splits") {
        BspTree tree;
        tree.build({});
        CHECK(tree.status() == BspStatus::Empty);
        CHECK(tree.classifyPoint(Vec3::Zero()) == BspPointClass::Outside);
        CHECK(!tree.segmentQuery({Vec3::Zero(), Vec3::Ones()}).hit);

        std::vector<BspPolygon> bad = cube();
        bad[2].vertices[1].y() = std::numeric_limits<double>::quiet_NaN();
        tree.build(bad);
        CHECK(tree.status() == BspStatus::InvalidInput);
        CHECK(tree.classifyPoint(Vec3::Zero()) == BspPointClass::Outside);

        std::mt19937 rng(5);
        std::vector<BspPolygon> withJunk = cube();
        withJunk.push_back({{Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)}});  // collinear: zero area
        withJunk.push_back({{Vec3(0, 0, 0), Vec3(1, 0, 0)}});                 // two vertices
        withJunk.push_back({{Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(0, 0, 0)}});  // one point
        tree.build(withJunk);
        CHECK(tree.status() == BspStatus::SomeDegenerate);
        CHECK(tree.classifyPoint(Vec3(0.5, 0.5, 0.5)) == BspPointClass::Inside);
        CHECK(tree.classifyPoint(Vec3(1.5, 0.5, 0.5)) == BspPointClass::Outside);
        tree.build({withJunk.back()});
        CHECK(tree.status() == BspStatus::SomeDegenerate);
        CHECK(tree.classifyPoint(Vec3::Zero()) == BspPointClass::Outside);

        // Each cube face as two coplanar triangles, plus duplicated faces: same solid.
        std::vector<BspPolygon> tris;
        for (const BspPolygon& f : cube()) {
            tris.push_back({{f.vertices[0], f.vertices[1], f.vertices[2]}});
            tris.push_back({{f.vertices[0], f.vertices[2], f.vertices[3]}});
            tris.push_back(tris.back());
        }
        tree.build(tris);
        CHECK(tree.status() == BspStatus::Ok);
        CHECK(tree.stats().innerCount == 6);
        CHECK(tree.fragments().size() == 18u);
        for (const Vec3& p : samplePoints(cube(), rng, 100, 0.01))
            CHECK(tree.classifyPoint(p) ==
                  (p.cwiseAbs().maxCoeff() < 1 ? BspPointClass::Inside : BspPointClass::Outside));

        // Segments lying in a face plane touch the closed solid; degenerate segment is a point query.
        tree.build(cube());
        const BspRayResult along = tree.segmentQuery({Vec3(-3, 0.2, 1), Vec3(3, 0.2, 1)});
        CHECK(along.hit);
        CHECK(std::abs(along.t - 2.0 / 6.0) < 1e-9);
        CHECK(tree.segmentQuery({Vec3(0.2, 0.2, 0.2), Vec3(0.2, 0.2, 0.2)}).startsInside);
        CHECK(!tree.segmentQuery({Vec3(2, 2, 2), Vec3(2, 2, 2)}).hit);
        CHECK(!tree.segmentQuery({Vec3(-3, 0.2, 1.5), Vec3(3, 0.2, 1.5)}).hit);
        CHECK(!tree.rayQuery({Vec3(0, 0, 0), Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0)}).hit);
        // Ray from outside, through the cube: enters at x = -1.
        const BspRayResult ray = tree.rayQuery({Vec3(-5, 0.1, 0.2), Vec3(2, 0, 0)});
        CHECK(ray.hit);
        CHECK(std::abs(ray.t - 2.0) < 1e-12);
        CHECK(std::abs(ray.point.x() + 1.0) < 1e-12);

        // Depth limit: a clear status and no crash.
        BspOptions shallow;
        shallow.maxDepth = 2;
        tree.build(torus(2.0, 0.7, 8, 6), shallow);
        CHECK(tree.status() == BspStatus::DepthLimit);
        CHECK(tree.stats().depth <= 2);
    }

}  // TEST_SUITE
