// Closest point on a tetrahedron with exact Voronoi-region choice.
// Ericson, Real-Time Collision Detection §5.1.6.
#include "core/closest/closest_point.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>

#include <Eigen/Core>

#include "core/base/exact_predicates.h"
#include "core/base/types.h"
#include "core/closest/closest_point_internal.h"

namespace cdlab {

using exact::BigDyadic;
using exact::Bounded;

namespace {

using closest_internal::EdgePoint;
using closest_internal::edgeInterior;
using closest_internal::FacePoint;
using closest_internal::faceInterior;

constexpr char kLetter[4] = {'a', 'b', 'c', 'd'};
constexpr int kTetEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                 {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};                // x, y, then the others
constexpr int kTetFaces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};  // x, y, z, opposite

// Names for the tetrahedron's predicates and conditions, built once (static storage, so the
// const char* in traces stay valid for the program's lifetime).
struct TetNames {
    std::string dotName[4][4];      // "(p-a).(b-a)"
    std::string sideName[4][4][4];  // edge (x<y), third z: "side(ab|c)"
    std::string sideFormula[4][4][4];
    std::string planeName[4];  // face opposite w: "side(abc|d)"
    std::string planeFormula[4];
    std::string condition[15];
};

std::string letters(std::initializer_list<int> indices) {
    std::string s;
    for (int i : indices) s += kLetter[i];
    return s;
}

const TetNames& tetNames() {
    static const TetNames names = [] {
        TetNames n;
        for (int x = 0; x < 4; ++x) {
            for (int y = 0; y < 4; ++y) {
                n.dotName[x][y] = "(p-" + letters({x}) + ").(" + letters({y}) + "-" + letters({x}) + ")";
                for (int z = 0; z < 4; ++z) {
                    n.sideName[x][y][z] = "side(" + letters({x, y}) + "|" + letters({z}) + ")";
                    const std::string X = letters({x}), Y = letters({y}), Z = letters({z});
                    n.sideFormula[x][y][z] =
                        "((" + Y + "-" + X + ")x(" + Z + "-" + X + ")).((p-" + X + ")x(p-" + Y + "))";
                }
            }
        }
        for (const auto& f : kTetFaces) {
            const std::string face = letters({f[0], f[1], f[2]});
            n.planeName[f[3]] = "side(" + face + "|" + letters({f[3]}) + ")";
            n.planeFormula[f[3]] = "orient(" + face + ",p)*sign(orient(" + face + "," + letters({f[3]}) + "))";
        }
        for (int v = 0; v < 4; ++v) {
            std::string cond;
            for (int y = 0; y < 4; ++y) {
                if (y == v) continue;
                cond += (cond.empty() ? "" : " && ") + n.dotName[v][y] + " <= 0";
            }
            n.condition[v] = cond;
        }
        for (int e = 0; e < 6; ++e) {
            const int* q = kTetEdges[e];
            n.condition[4 + e] = n.dotName[q[0]][q[1]] + " >= 0 && " + n.dotName[q[1]][q[0]] + " >= 0 && " +
                                 n.sideName[q[0]][q[1]][q[2]] + " <= 0 && " + n.sideName[q[0]][q[1]][q[3]] + " <= 0";
        }
        for (int f = 0; f < 4; ++f) {
            const int* q = kTetFaces[f];
            n.condition[10 + f] = n.planeName[q[3]] + " <= 0 && " + n.sideName[q[0]][q[1]][q[2]] + " >= 0 && " +
                                  n.sideName[q[1]][q[2]][q[0]] + " >= 0 && " + n.sideName[q[0]][q[2]][q[1]] + " >= 0";
        }
        return n;
    }();
    return names;
}

TetrahedronRegion tetEdgeRegion(int i, int j) {
    const int lo = std::min(i, j), hi = std::max(i, j);
    for (int e = 0; e < 6; ++e) {
        if (kTetEdges[e][0] == lo && kTetEdges[e][1] == hi) return static_cast<TetrahedronRegion>(4 + e);
    }
    return TetrahedronRegion::AB;
}

TetrahedronRegion tetFaceRegion(int opposite) {
    for (int f = 0; f < 4; ++f) {
        if (kTetFaces[f][3] == opposite) return static_cast<TetrahedronRegion>(10 + f);
    }
    return TetrahedronRegion::ABC;
}

// (Out of line: the exact evaluation is rare, and inlining it would make every caller larger.)
template <class Expression>
[[gnu::noinline]] int exactTermSign(const Expression& expression, bool inputsInRange) {
    return exact::exactSign(expression, inputsInRange);
}

// Evaluates one exact term and records it.
template <class Expression>
PredicateSign tetTerm(const char* name, const char* formula, int orientation, bool inputsInRange,
                      const Expression& expression) {
    PredicateSign out;
    out.name = name;
    out.formula = formula;
    const Bounded approx = expression(Bounded{});
    out.value = orientation * approx.value;
    out.sign = exact::certainSign(approx);
    if (out.sign == 0) {
        out.exactFallback = true;
        out.sign = exactTermSign(expression, inputsInRange);
    }
    out.sign *= orientation;
    return out;
}

// The four vertices with vertex i replaced by p.
std::array<const Vec3*, 4> withP(const Vec3& p, const Vec3* const v[4], int i) {
    std::array<const Vec3*, 4> u = {v[0], v[1], v[2], v[3]};
    u[i] = &p;
    return u;
}

// Barycentric weights of p inside the tetrahedron: the volume ratios orient(a..p..d) /
// orient(a,b,c,d). In the plain range in double, clamped against rounding and normalised;
// outside it, exact rationals rounded once (within one ulp; they sum to 1 exactly
// before rounding).
[[gnu::noinline, gnu::cold]] Eigen::Vector4d exactInsideWeights(const Vec3& p, const Vec3* const v[4]) {
    const BigDyadic volume = exact::orient3d<BigDyadic>(*v[0], *v[1], *v[2], *v[3]);
    Eigen::Vector4d w;
    for (int i = 0; i < 4; ++i) {
        const auto u = withP(p, v, i);
        w[i] = std::clamp(exact::quotient(exact::orient3d<BigDyadic>(*u[0], *u[1], *u[2], *u[3]), volume), 0.0, 1.0);
    }
    return w;
}

Eigen::Vector4d insideWeights(const Vec3& p, const Vec3* const v[4], bool plain) {
    if (!plain) return exactInsideWeights(p, v);
    Eigen::Vector4d w;
    const double volume = exact::orient3d<double>(*v[0], *v[1], *v[2], *v[3]);
    for (int i = 0; i < 4; ++i) {
        const auto u = withP(p, v, i);
        w[i] = std::max(0.0, exact::orient3d<double>(*u[0], *u[1], *u[2], *u[3]) / volume);
    }
    const double sum = w.sum();
    // A thin tetrahedron's volume may round to 0 (exact sign nonzero): equal weights then.
    return std::isfinite(sum) && sum > 0.0 ? Eigen::Vector4d(w / sum) : Eigen::Vector4d::Constant(0.25);
}

ClosestPointOnTetrahedronResult degenerateTetrahedron(const Vec3& p, const Vec3* v[4]) {
    // Flat: the point set is the union of the four (possibly degenerate) faces; the best face
    // wins, the first one on ties.
    ClosestPointOnTetrahedronResult best;
    best.distanceSquared = std::numeric_limits<double>::infinity();
    for (const auto& f : kTetFaces) {
        const ClosestPointOnTriangleResult r = closestPointOnTriangle(p, Triangle{*v[f[0]], *v[f[1]], *v[f[2]]});
        if (!(r.distanceSquared < best.distanceSquared)) continue;
        best.point = r.point;
        best.distanceSquared = r.distanceSquared;
        best.barycentric.setZero();
        for (int k = 0; k < 3; ++k) best.barycentric[f[k]] = r.barycentric[k];
        switch (r.region) {
            case TriangleRegion::A: best.region = static_cast<TetrahedronRegion>(f[0]); break;
            case TriangleRegion::B: best.region = static_cast<TetrahedronRegion>(f[1]); break;
            case TriangleRegion::C: best.region = static_cast<TetrahedronRegion>(f[2]); break;
            case TriangleRegion::AB: best.region = tetEdgeRegion(f[0], f[1]); break;
            case TriangleRegion::BC: best.region = tetEdgeRegion(f[1], f[2]); break;
            case TriangleRegion::CA: best.region = tetEdgeRegion(f[2], f[0]); break;
            case TriangleRegion::ABC: best.region = tetFaceRegion(f[3]); break;
        }
    }
    best.status = SimplexStatus::Degenerate;
    return best;
}

ClosestPointOnTetrahedronResult nonFiniteTetrahedronResult() {
    ClosestPointOnTetrahedronResult r;
    r.point = Vec3::Constant(kNaN);
    r.barycentric = Eigen::Vector4d::Constant(kNaN);
    r.distanceSquared = kNaN;
    r.status = SimplexStatus::NonFinite;
    return r;
}

// The last test of the trace: every closed region of a boundary feature rejected, p is inside.
RegionTest<TetrahedronRegion, 4> insideTest() {
    RegionTest<TetrahedronRegion, 4> test;
    test.candidate = TetrahedronRegion::ABCD;
    test.condition = "otherwise (p inside)";
    test.accepted = true;
    return test;
}

}  // namespace

// Ericson, "Real-Time Collision Detection", §5.1.6: the Voronoi region of p among the vertices,
// edges and faces of the tetrahedron, each region's test decided by exact signs.
ClosestPointOnTetrahedronResult closestPointOnTetrahedron(const Vec3& p, const Tetrahedron& t,
                                                          TetrahedronTrace* trace) {
    if (trace) trace->tests.clear();
    auto done = [&](const ClosestPointOnTetrahedronResult& r) {
        if (trace) trace->result = r;
        return r;
    };
    const Vec3* v[4] = {&t.a, &t.b, &t.c, &t.d};
    // One pass classifies the input (see closestPointOnTriangle).
    const bool plain = exact::inExpansionRange({&p, &t.a, &t.b, &t.c, &t.d});
    if (!plain && (!p.allFinite() || !t.a.allFinite() || !t.b.allFinite() || !t.c.allFinite() || !t.d.allFinite())) {
        return done(nonFiniteTetrahedronResult());
    }
    const int volumeSign = exact::orient3dSign(t.a, t.b, t.c, t.d);
    if (volumeSign == 0) return done(degenerateTetrahedron(p, v));

    const TetNames& names = tetNames();
    auto dotTerm = [&](int x, int y) {  // (p-x)·(y-x)
        return tetTerm(names.dotName[x][y].c_str(), names.dotName[x][y].c_str(), 1, plain,
                       [&](auto zero) { return exact::dotOfDifferences<decltype(zero)>(*v[x], p, *v[x], *v[y]); });
    };
    auto sideTerm = [&](int x, int y, int z) {  // in-face side of edge xy (symmetric in x, y)
        if (x > y) std::swap(x, y);
        return tetTerm(names.sideName[x][y][z].c_str(), names.sideFormula[x][y][z].c_str(), 1, plain,
                       [&](auto zero) { return exact::edgeSide<decltype(zero)>(*v[x], *v[y], *v[z], p); });
    };
    auto planeTerm = [&](const int* f) {  // p's side of face plane, positive = the opposite vertex's side
        const int orientation = exact::orient3dSign(*v[f[0]], *v[f[1]], *v[f[2]], *v[f[3]]);
        return tetTerm(names.planeName[f[3]].c_str(), names.planeFormula[f[3]].c_str(), orientation, plain,
                       [&](auto zero) { return exact::orient3d<decltype(zero)>(*v[f[0]], *v[f[1]], *v[f[2]], p); });
    };

    ClosestPointOnTetrahedronResult r;
    // Runs one closed-region test: terms evaluated in order until one fails.
    auto runTest = [&](TetrahedronRegion candidate, auto&& terms) {
        RegionTest<TetrahedronRegion, 4> test;
        test.candidate = candidate;
        test.condition = names.condition[static_cast<int>(candidate)].c_str();
        test.accepted = terms(test);
        if (trace) trace->tests.push_back(test);
        return test.accepted;
    };
    auto require = [](RegionTest<TetrahedronRegion, 4>& test, const PredicateSign& term, bool nonPositive) {
        test.terms[test.termCount++] = term;
        return nonPositive ? term.sign <= 0 : term.sign >= 0;
    };

    // Vertex regions: (p-x)·(y-x) <= 0 for the three other vertices y.
    for (int x = 0; x < 4; ++x) {
        const bool accepted = runTest(static_cast<TetrahedronRegion>(x), [&](auto& test) {
            for (int y = 0; y < 4; ++y) {
                if (y != x && !require(test, dotTerm(x, y), true)) return false;
            }
            return true;
        });
        if (accepted) {
            r.region = static_cast<TetrahedronRegion>(x);
            r.point = *v[x];
            r.barycentric = Eigen::Vector4d::Unit(x);
            r.distanceSquared = (p - r.point).squaredNorm();
            return done(r);
        }
    }
    // Edge regions: p projects into [x, y] and lies outside both faces at the edge, in-plane.
    for (int e = 0; e < 6; ++e) {
        const int* q = kTetEdges[e];
        const TetrahedronRegion region = static_cast<TetrahedronRegion>(4 + e);
        const bool accepted = runTest(region, [&](auto& test) {
            return require(test, dotTerm(q[0], q[1]), false) && require(test, dotTerm(q[1], q[0]), false) &&
                   require(test, sideTerm(q[0], q[1], q[2]), true) && require(test, sideTerm(q[0], q[1], q[3]), true);
        });
        if (accepted) {
            const EdgePoint ep = edgeInterior(p, *v[q[0]], *v[q[1]], plain);
            r.region = region;
            r.point = ep.point;
            r.barycentric.setZero();
            r.barycentric[q[0]] = ep.r;
            r.barycentric[q[1]] = ep.s;
            r.distanceSquared = (p - r.point).squaredNorm();
            return done(r);
        }
    }
    // Face regions: p not strictly on the inner side of the face plane, and projecting into the
    // closed face.
    for (int f = 0; f < 4; ++f) {
        const int* q = kTetFaces[f];
        const TetrahedronRegion region = static_cast<TetrahedronRegion>(10 + f);
        const bool accepted = runTest(region, [&](auto& test) {
            return require(test, planeTerm(q), true) && require(test, sideTerm(q[0], q[1], q[2]), false) &&
                   require(test, sideTerm(q[1], q[2], q[0]), false) && require(test, sideTerm(q[0], q[2], q[1]), false);
        });
        if (accepted) {
            const FacePoint fp = faceInterior(p, *v[q[0]], *v[q[1]], *v[q[2]], plain);
            r.region = region;
            r.point = fp.point;
            r.barycentric.setZero();
            for (int k = 0; k < 3; ++k) r.barycentric[q[k]] = fp.weights[k];
            r.distanceSquared = (p - r.point).squaredNorm();
            return done(r);
        }
    }
    // Inside (all closed regions of the boundary features rejected): p itself.
    r.region = TetrahedronRegion::ABCD;
    r.point = p;
    r.distanceSquared = 0.0;
    r.barycentric = insideWeights(p, v, plain);
    if (trace) trace->tests.push_back(insideTest());
    return done(r);
}

}  // namespace cdlab
