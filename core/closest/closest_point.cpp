// Closest points on segments and triangles with exact Voronoi-region choice (tetrahedra:
// closest_point_tetrahedron.cpp). Ericson, Real-Time Collision Detection §5.1.2, §5.1.5, §5.1.9.
#include "core/closest/closest_point.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "core/base/exact_predicates.h"
#include "core/base/power_of_two.h"
#include "core/closest/closest_point_internal.h"

namespace cdlab {

using exact::BigDyadic;
using exact::Bounded;
using exact::Expansion;

const char* nameOf(SegmentRegion region) {
    switch (region) {
        case SegmentRegion::A: return "A";
        case SegmentRegion::B: return "B";
        case SegmentRegion::AB: return "AB";
    }
    return "?";
}

const char* nameOf(TriangleRegion region) {
    switch (region) {
        case TriangleRegion::A: return "A";
        case TriangleRegion::B: return "B";
        case TriangleRegion::C: return "C";
        case TriangleRegion::AB: return "AB";
        case TriangleRegion::BC: return "BC";
        case TriangleRegion::CA: return "CA";
        case TriangleRegion::ABC: return "ABC";
    }
    return "?";
}

const char* nameOf(TetrahedronRegion region) {
    static constexpr const char* kNames[] = {"A",  "B",  "C",   "D",   "AB",  "AC",  "AD",  "BC",
                                             "BD", "CD", "ABC", "ABD", "ACD", "BCD", "ABCD"};
    const int i = static_cast<int>(region);
    return (i >= 0 && i < 15) ? kNames[i] : "?";
}

namespace {

using closest_internal::EdgePoint;
using closest_internal::edgeInterior;
using closest_internal::FacePoint;
using closest_internal::faceInterior;

// ---------------------------------------------------------------------------------------------
// Triangle: Ericson's quantities, filtered in double, exact on demand.

enum Quantity { D1, D2, D3, D4, D5, D6, D43, D56, VA, VB, VC, kQuantityCount };

constexpr const char* kQuantityName[kQuantityCount] = {"d1",    "d2",    "d3", "d4", "d5", "d6",
                                                       "d4-d3", "d5-d6", "va", "vb", "vc"};
constexpr const char* kQuantityFormula[kQuantityCount] = {
    "(b-a).(p-a)", "(c-a).(p-a)", "(b-a).(p-b)",   "(c-a).(p-b)",   "(b-a).(p-c)",  "(c-a).(p-c)",
    "(c-b).(p-b)", "(b-c).(p-c)", "d3*d6 - d5*d4", "d5*d2 - d1*d6", "d1*d4 - d3*d2"};

class TriangleSigns {
public:
    // The coordinate differences are shared by all quantities: computed once, as Bounded values
    // (each carries its own rounding error), and the quantities on demand, in Ericson's order.
    TriangleSigns(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, bool inputsInRange)
        : p_(p), a_(a), b_(b), c_(c), inputsInRange_(inputsInRange) {
        for (int i = 0; i < 3; ++i) {
            ab_[i] = Bounded(b[i]) - Bounded(a[i]);
            ac_[i] = Bounded(c[i]) - Bounded(a[i]);
            bc_[i] = Bounded(c[i]) - Bounded(b[i]);
            ap_[i] = Bounded(p[i]) - Bounded(a[i]);
            bp_[i] = Bounded(p[i]) - Bounded(b[i]);
            cp_[i] = Bounded(p[i]) - Bounded(c[i]);
        }
    }

    /// Cheap pre-test: true when the filter already certifies (b-a)×(c-a) != 0.
    bool certainlyNotCollinear() const {
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3, k = (i + 2) % 3;
            if (exact::certainSign(ab_[j] * ac_[k] - ab_[k] * ac_[j]) != 0) return true;
        }
        return false;
    }

    PredicateSign evaluate(Quantity q) {
        const Bounded& approx = approximate(q);
        PredicateSign out;
        out.name = kQuantityName[q];
        out.formula = kQuantityFormula[q];
        out.value = approx.value;
        out.sign = exact::certainSign(approx);
        if (out.sign == 0) {
            out.exactFallback = true;
            out.sign = exactSign(q);
        }
        return out;
    }

private:
    static Bounded dot3(const Bounded* x, const Bounded* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }

    const Bounded& approximate(Quantity q) {
        if (have_[q]) return approx_[q];
        switch (q) {
            case D1: approx_[q] = dot3(ab_, ap_); break;
            case D2: approx_[q] = dot3(ac_, ap_); break;
            case D3: approx_[q] = dot3(ab_, bp_); break;
            case D4: approx_[q] = dot3(ac_, bp_); break;
            case D5: approx_[q] = dot3(ab_, cp_); break;
            case D6: approx_[q] = dot3(ac_, cp_); break;
            // d4 - d3 = (c-b)·(p-b) and d5 - d6 = (b-c)·(p-c) exactly; filtering the direct dot
            // product is tighter than filtering the difference.
            case D43: approx_[q] = dot3(bc_, bp_); break;
            case D56: {
                const Bounded cb[3] = {Bounded() - bc_[0], Bounded() - bc_[1], Bounded() - bc_[2]};  // exact negation
                approx_[q] = dot3(cb, cp_);
                break;
            }
            case VA: approx_[q] = approximate(D3) * approximate(D6) - approximate(D5) * approximate(D4); break;
            case VB: approx_[q] = approximate(D5) * approximate(D2) - approximate(D1) * approximate(D6); break;
            case VC: approx_[q] = approximate(D1) * approximate(D4) - approximate(D3) * approximate(D2); break;
            default: break;
        }
        have_[q] = true;
        return approx_[q];
    }

    template <class T>
    T dot(Quantity q) const {
        switch (q) {
            case D1: return exact::dotOfDifferences<T>(a_, b_, a_, p_);
            case D2: return exact::dotOfDifferences<T>(a_, c_, a_, p_);
            case D3: return exact::dotOfDifferences<T>(a_, b_, b_, p_);
            case D4: return exact::dotOfDifferences<T>(a_, c_, b_, p_);
            case D5: return exact::dotOfDifferences<T>(a_, b_, c_, p_);
            case D6: return exact::dotOfDifferences<T>(a_, c_, c_, p_);
            case D43: return exact::dotOfDifferences<T>(b_, c_, b_, p_);
            default: return exact::dotOfDifferences<T>(c_, b_, c_, p_);  // D56
        }
    }

    // Exact sign, as exact::exactSign: expansions where ExponentBounds shows them exact,
    // BigDyadic otherwise. Both kinds of value are cached: va, vb, vc reuse d1..d6.
    // When all twelve coordinates are in ExponentBounds' input range, every quantity is
    // expansion-safe (degree <= 4, 3-term sums: high <= 973, grain >= -1008); otherwise each
    // quantity is checked on the coordinates it reads. (Out of line: rare, and inlining it
    // would make every caller larger.)
    [[gnu::noinline]] int exactSign(Quantity q) {
        if (inputsInRange_ || value<exact::ExponentBounds>(q).safe) return exactValue<Expansion>(q).sign();
        return bigDyadicSign(q);
    }
    [[gnu::noinline, gnu::cold]] int bigDyadicSign(Quantity q) { return exactValue<BigDyadic>(q).sign(); }

    // Quantity q in number type T, from scratch (for ExponentBounds, which is cheap).
    template <class T>
    T value(Quantity q) const {
        switch (q) {
            case VA: return value<T>(D3) * value<T>(D6) - value<T>(D5) * value<T>(D4);
            case VB: return value<T>(D5) * value<T>(D2) - value<T>(D1) * value<T>(D6);
            case VC: return value<T>(D1) * value<T>(D4) - value<T>(D3) * value<T>(D2);
            default: return dot<T>(q);
        }
    }

    template <class T>
    const T& exactValue(Quantity q) {
        std::optional<T>& slot = cacheSlot<T>(q);
        if (slot) return *slot;
        T v;
        switch (q) {
            case VA: v = exactValue<T>(D3) * exactValue<T>(D6) - exactValue<T>(D5) * exactValue<T>(D4); break;
            case VB: v = exactValue<T>(D5) * exactValue<T>(D2) - exactValue<T>(D1) * exactValue<T>(D6); break;
            case VC: v = exactValue<T>(D1) * exactValue<T>(D4) - exactValue<T>(D3) * exactValue<T>(D2); break;
            default: v = dot<T>(q); break;
        }
        slot = std::move(v);
        return *slot;
    }

    template <class T>
    std::optional<T>& cacheSlot(Quantity q) {
        if constexpr (std::is_same_v<T, Expansion>) {
            return exact_[q];
        } else {
            // Allocated only on the out-of-range path, so the common case pays nothing for it.
            if (!dyadic_) dyadic_ = std::make_unique<std::array<std::optional<BigDyadic>, kQuantityCount>>();
            return (*dyadic_)[q];
        }
    }

    Vec3 p_, a_, b_, c_;
    Bounded ab_[3], ac_[3], bc_[3], ap_[3], bp_[3], cp_[3];
    Bounded approx_[kQuantityCount];
    bool have_[kQuantityCount] = {};
    bool inputsInRange_;
    std::optional<Expansion> exact_[kQuantityCount];
    std::unique_ptr<std::array<std::optional<BigDyadic>, kQuantityCount>> dyadic_;
};

struct TermSpec {
    Quantity quantity;
    bool nonPositive;  // the term is "quantity <= 0" (else "quantity >= 0")
};
struct TriangleTestSpec {
    TriangleRegion region;
    const char* condition;
    int termCount;
    TermSpec terms[3];
};

// Ericson's order and comparisons (ClosestPtPointTriangle, §5.1.5). "d4 <= d3" is the sign of
// d4 - d3 = (c-b)·(p-b); "d5 <= d6" the sign of d5 - d6 = (b-c)·(p-c).
constexpr TriangleTestSpec kTriangleTests[] = {
    {TriangleRegion::A, "d1 <= 0 && d2 <= 0", 2, {{D1, true}, {D2, true}, {D1, true}}},
    {TriangleRegion::B, "d3 >= 0 && d4 <= d3", 2, {{D3, false}, {D43, true}, {D1, true}}},
    {TriangleRegion::AB, "vc <= 0 && d1 >= 0 && d3 <= 0", 3, {{VC, true}, {D1, false}, {D3, true}}},
    {TriangleRegion::C, "d6 >= 0 && d5 <= d6", 2, {{D6, false}, {D56, true}, {D1, true}}},
    {TriangleRegion::CA, "vb <= 0 && d2 >= 0 && d6 <= 0", 3, {{VB, true}, {D2, false}, {D6, true}}},
    {TriangleRegion::BC, "va <= 0 && d4-d3 >= 0 && d5-d6 >= 0", 3, {{VA, true}, {D43, false}, {D56, false}}},
};

ClosestPointOnTriangleResult nonFiniteTriangle() {
    ClosestPointOnTriangleResult r;
    r.point = Vec3::Constant(kNaN);
    r.barycentric = Vec3::Constant(kNaN);
    r.distanceSquared = kNaN;
    r.status = SimplexStatus::NonFinite;
    return r;
}

TriangleRegion edgeRegion(int i, int j) {
    const int lo = std::min(i, j), hi = std::max(i, j);
    if (lo == 0 && hi == 1) return TriangleRegion::AB;
    if (lo == 1 && hi == 2) return TriangleRegion::BC;
    return TriangleRegion::CA;
}

// Collinear (or repeated) vertices: the point set is the segment between the two extreme
// vertices. Region: the vertex if the closest point is exactly one (the first of equal vertices),
// else the spanning edge (the first of AB, BC, CA that spans the set).
ClosestPointOnTriangleResult degenerateTriangle(const Vec3& p, const Triangle& t) {
    const Vec3* v[3] = {&t.a, &t.b, &t.c};
    ClosestPointOnTriangleResult r;
    r.status = SimplexStatus::Degenerate;
    auto setVertex = [&](int i) {
        for (int k = 0; k < i; ++k) {
            if (*v[k] == *v[i]) i = k;  // canonical label among repeated vertices
        }
        r.region = static_cast<TriangleRegion>(i);
        r.point = *v[i];
        r.barycentric = Vec3::Unit(i);
    };
    // Spanning edge: x, y such that the third vertex z lies between them, (x-z)·(y-z) <= 0.
    static constexpr int kEdges[3][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}};
    int e = 0;
    while (e < 2 && exact::dotSign(*v[kEdges[e][2]], *v[kEdges[e][0]], *v[kEdges[e][2]], *v[kEdges[e][1]]) > 0) ++e;
    const int x = kEdges[e][0], y = kEdges[e][1], z = kEdges[e][2];
    const ClosestPointOnSegmentResult seg = closestPointOnSegment(p, Segment{*v[x], *v[y]});
    if (seg.region == SegmentRegion::A) {
        setVertex(x);
    } else if (seg.region == SegmentRegion::B) {
        setVertex(y);
    } else if (*v[z] != *v[x] && *v[z] != *v[y] && exact::dotSign(*v[x], *v[y], *v[z], p) == 0) {
        setVertex(z);  // p projects exactly onto the middle vertex
    } else {
        r.region = edgeRegion(x, y);
        r.point = seg.point;
        r.barycentric = Vec3::Zero();
        r.barycentric[x] = 1.0 - seg.t;
        r.barycentric[y] = seg.t;
    }
    r.distanceSquared = (p - r.point).squaredNorm();
    return r;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Segments

ClosestPointOnSegmentResult closestPointOnSegment(const Vec3& p, const Segment& s) {
    ClosestPointOnSegmentResult r;
    // One pass classifies the input: in the expansion range (so finite: plain arithmetic), or not.
    const bool plain = exact::inExpansionRange({&p, &s.a, &s.b});
    if (!plain && (!p.allFinite() || !s.a.allFinite() || !s.b.allFinite())) {
        r.point = Vec3::Constant(kNaN);
        r.t = r.distanceSquared = kNaN;
        return r;
    }
    // Ericson §5.1.2 with exact signs: t = (p-a)·(b-a) / |b-a|^2 clamped to [0, 1].
    if (exact::dotSign(s.a, s.b, s.a, p) <= 0) {  // (b-a)·(p-a) <= 0: before a (or a == b)
        r.point = s.a;
        r.t = 0.0;
        r.region = SegmentRegion::A;
    } else if (exact::dotSign(s.b, s.a, s.b, p) <= 0) {  // (a-b)·(p-b) <= 0: beyond b
        r.point = s.b;
        r.t = 1.0;
        r.region = SegmentRegion::B;
    } else {
        const EdgePoint e = edgeInterior(p, s.a, s.b, plain);
        r.point = e.point;
        r.t = e.s;
        r.region = SegmentRegion::AB;
    }
    r.distanceSquared = (p - r.point).squaredNorm();
    return r;
}

SegmentSegmentResult closestPointsSegmentSegment(const Segment& first, const Segment& second) {
    SegmentSegmentResult r;
    if (!first.a.allFinite() || !first.b.allFinite() || !second.a.allFinite() || !second.b.allFinite()) {
        r.s = r.t = r.distanceSquared = kNaN;
        r.pointOnFirst = r.pointOnSecond = Vec3::Constant(kNaN);
        return r;
    }
    auto finish = [&](double s, double t) {
        r.s = s;
        r.t = t;
        r.pointOnFirst = first.a + s * (first.b - first.a);
        r.pointOnSecond = second.a + t * (second.b - second.a);
        if (s == 1.0) r.pointOnFirst = first.b;  // endpoints exactly, not a + 1*(b-a)
        if (t == 1.0) r.pointOnSecond = second.b;
        r.distanceSquared = (r.pointOnFirst - r.pointOnSecond).squaredNorm();
        return r;
    };
    // Ericson §5.1.9 notation: d1, d2 directions, r = p1 - p2. s and t do not depend on scale, and
    // a, e, b, c, f are squares of coordinate differences, which overflow above ~1e154 (boxes of
    // half-size 1e78 gave NaN points) and vanish below ~1e-154: the differences are taken to a
    // largest magnitude in [1, 2) by a power of two first, exact (halved before subtracting when a
    // difference itself would overflow), so every representable input has the same s and t as its
    // scaled copy and moderate inputs their unscaled values bit for bit.
    Vec3 d1 = first.b - first.a, d2 = second.b - second.a, rr = first.a - second.a;
    if (!d1.allFinite() || !d2.allFinite() || !rr.allFinite())
        d1 = 0.5 * first.b - 0.5 * first.a, d2 = 0.5 * second.b - 0.5 * second.a, rr = 0.5 * first.a - 0.5 * second.a;
    const double largest = std::max({d1.cwiseAbs().maxCoeff(), d2.cwiseAbs().maxCoeff(), rr.cwiseAbs().maxCoeff()});
    if (largest > 0.0) {
        // x * 2^k as ldexp gives it (k = -ilogb(largest) is in [-1023, 1074]: PowerOfTwo's range).
        const PowerOfTwo scale(-std::ilogb(largest));
        d1 = d1.unaryExpr(scale), d2 = d2.unaryExpr(scale), rr = rr.unaryExpr(scale);
    }
    const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(rr);
    // Zero length: a below the smallest normal double (the segment shorter than ~1e-154 of the
    // largest difference, after the scaling) would overflow 1/a; such a segment is a point.
    constexpr double kZeroLength = std::numeric_limits<double>::min();
    const bool firstPoint = a < kZeroLength, secondPoint = e < kZeroLength;
    if (firstPoint || secondPoint) r.degenerate = true;
    if (firstPoint && secondPoint) return finish(0.0, 0.0);
    if (firstPoint) return finish(0.0, closestPointOnSegment(first.a, second).t);
    if (secondPoint) return finish(closestPointOnSegment(second.a, first).t, 0.0);

    const double c = d1.dot(rr), b = d1.dot(d2);
    const double denom = a * e - b * b;  // = a e sin^2(angle) >= 0
    // a*e - b*b carries an absolute rounding error of a few u * a*e (u = 1.1e-16). Below 1e-14 a e
    // (angle below ~1e-7 rad) its value is noise, so the segments are treated as parallel.
    constexpr double kParallel = 1e-14;
    if (denom > kParallel * a * e) {
        double s = std::clamp((b * f - c * e) / denom, 0.0, 1.0);
        double t = (b * s + f) / e;
        // t outside [0, 1]: clamp t and recompute s for the clamped t (Ericson).
        if (t < 0.0) {
            t = 0.0;
            s = std::clamp(-c / a, 0.0, 1.0);
        } else if (t > 1.0) {
            t = 1.0;
            s = std::clamp((b - c) / a, 0.0, 1.0);
        }
        return finish(s, t);
    }
    // (Nearly) parallel: some closest pair has an endpoint of one segment; take the best of the
    // four endpoint-to-segment pairs (first wins ties, so the answer is deterministic).
    r.parallel = true;
    const ClosestPointOnSegmentResult q[4] = {
        closestPointOnSegment(first.a, second), closestPointOnSegment(first.b, second),
        closestPointOnSegment(second.a, first), closestPointOnSegment(second.b, first)};
    int best = 0;
    for (int i = 1; i < 4; ++i) {
        if (q[i].distanceSquared < q[best].distanceSquared) best = i;
    }
    switch (best) {
        case 0: return finish(0.0, q[0].t);
        case 1: return finish(1.0, q[1].t);
        case 2: return finish(q[2].t, 0.0);
        default: return finish(q[3].t, 1.0);
    }
}

// ---------------------------------------------------------------------------------------------
// Triangles

ClosestPointOnTriangleResult closestPointOnTriangle(const Vec3& p, const Triangle& t, ClosestPointTrace* trace) {
    if (trace) trace->tests.clear();
    auto done = [&](const ClosestPointOnTriangleResult& r) {
        if (trace) trace->result = r;
        return r;
    };
    // One pass classifies the input: in the expansion range (so finite: expansions and plain
    // double points), or not (BigDyadic where needed), or not finite.
    const bool plain = exact::inExpansionRange({&p, &t.a, &t.b, &t.c});
    if (!plain && (!p.allFinite() || !t.a.allFinite() || !t.b.allFinite() || !t.c.allFinite()))
        return done(nonFiniteTriangle());
    TriangleSigns signs(p, t.a, t.b, t.c, plain);
    if (!signs.certainlyNotCollinear() && exact::collinear(t.a, t.b, t.c)) return done(degenerateTriangle(p, t));
    ClosestPointOnTriangleResult r;
    r.region = TriangleRegion::ABC;
    for (const TriangleTestSpec& spec : kTriangleTests) {
        RegionTest<TriangleRegion, 3> test;
        test.candidate = spec.region;
        test.condition = spec.condition;
        test.accepted = true;
        for (int k = 0; k < spec.termCount && test.accepted; ++k) {
            const PredicateSign term = signs.evaluate(spec.terms[k].quantity);
            test.terms[test.termCount++] = term;
            test.accepted = spec.terms[k].nonPositive ? term.sign <= 0 : term.sign >= 0;
        }
        if (trace) trace->tests.push_back(test);
        if (test.accepted) {
            r.region = spec.region;
            break;
        }
    }
    if (r.region == TriangleRegion::ABC && trace) {
        RegionTest<TriangleRegion, 3> test;
        test.candidate = TriangleRegion::ABC;
        test.condition = "otherwise (p projects inside the triangle)";
        test.accepted = true;
        trace->tests.push_back(test);
    }

    switch (r.region) {
        case TriangleRegion::A:
            r.point = t.a;
            r.barycentric = Vec3(1, 0, 0);
            break;
        case TriangleRegion::B:
            r.point = t.b;
            r.barycentric = Vec3(0, 1, 0);
            break;
        case TriangleRegion::C:
            r.point = t.c;
            r.barycentric = Vec3(0, 0, 1);
            break;
        case TriangleRegion::AB: {
            const EdgePoint e = edgeInterior(p, t.a, t.b, plain);
            r.point = e.point;
            r.barycentric = Vec3(e.r, e.s, 0.0);
            break;
        }
        case TriangleRegion::BC: {
            const EdgePoint e = edgeInterior(p, t.b, t.c, plain);
            r.point = e.point;
            r.barycentric = Vec3(0.0, e.r, e.s);
            break;
        }
        case TriangleRegion::CA: {
            const EdgePoint e = edgeInterior(p, t.c, t.a, plain);
            r.point = e.point;
            r.barycentric = Vec3(e.s, 0.0, e.r);
            break;
        }
        case TriangleRegion::ABC: {
            const FacePoint f = faceInterior(p, t.a, t.b, t.c, plain);
            r.point = f.point;
            r.barycentric = f.weights;
            break;
        }
    }
    r.distanceSquared = (p - r.point).squaredNorm();
    return done(r);
}

}  // namespace cdlab
