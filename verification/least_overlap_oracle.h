// Oracle for two polytopes' contact (`cdlab stress`, family "contact manifolds"): from the two
// vertex lists only, in long double with exact edge vectors, no hull and nothing of core's
// algorithms,
//   - the least overlap D* = min over unit n of h_{A−B}(n) = h_A(n) + h_B(−n), the minimum taken
//     over every triple normal of each body (a superset of their face normals) and every cross
//     product of a vertex pair of A with one of B (a superset of their edge pairs), both signs.
//     Every facet normal of A − B is among them, so D* is the penetration depth when positive;
//     any other unit direction has h_{A−B} >= the depth, so the extra candidates change nothing.
//     When D* <= 0 the bodies do not overlap (a facet normal of A − B separates them, or touches);
//   - the distance of two non-overlapping bodies by brute force over the feature pairs that hold a
//     closest pair: a vertex of one against every vertex triangle of the other, and every segment
//     pair (their Minkowski difference, a parallelogram: the projection of the origin when it falls
//     inside, else its four sides).
// Precision: each candidate normal is the cross product of two edge vectors p − q of doubles held
// exactly (hi + lo in long double), its products exact (Veltkamp split) and summed with the error
// of each sum kept (TwoSum), so its direction is right to ~2^-64 whatever the angle between the two
// edges (a plain long double cross product of edges 1e-12 rad apart is off by ~5e-8: the error of
// h along it would be that times the body size). Projections are long double dot products of
// vertices taken relative to one vertex of A (errors ~2^-64 of the pair's extent).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/base/types.h"
#include "verification/long_double_geometry.h"

namespace cdlab::verification::least_overlap {

using long_double::LVec;
using long_double::toL;

/// hi + lo, exactly.
struct Exact {
    long double hi = 0, lo = 0;
};

inline Exact twoSum(long double a, long double b) {
    const long double s = a + b, bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}

/// a · b exactly (Veltkamp's split of each 64-bit significand into two 32-bit halves, Dekker's product).
inline Exact twoProduct(long double a, long double b) {
    constexpr long double kSplit = 4294967297.0L;  // 2^32 + 1
    const auto split = [](long double x, long double& hi, long double& lo) {
        const long double t = kSplit * x;
        hi = t - (t - x);
        lo = x - hi;
    };
    long double ah, al, bh, bl;
    split(a, ah, al);
    split(b, bh, bl);
    const long double p = a * b;
    return {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
}

/// An edge vector q − p of two doubles, exactly.
using ExactVec = std::array<Exact, 3>;

inline ExactVec edge(const Vec3& p, const Vec3& q) {
    return {twoSum(q.x(), -p.x()), twoSum(q.y(), -p.y()), twoSum(q.z(), -p.z())};
}

/// u × w, each coordinate the sum of the exact partial products with every rounding error kept:
/// right to ~2^-64 of its own size (plus ~2^-120 |u| |w|).
inline LVec cross(const ExactVec& u, const ExactVec& w) {
    const auto det = [](const Exact& a, const Exact& b, const Exact& c, const Exact& d) {  // a b − c d
        long double s = 0, err = 0;
        const auto add = [&](long double x) {
            const Exact t = twoSum(s, x);
            s = t.hi;
            err += t.lo;
        };
        const Exact p = twoProduct(a.hi, b.hi), q = twoProduct(c.hi, d.hi);
        add(p.hi);
        add(-q.hi);
        add(p.lo);
        add(-q.lo);
        add(a.hi * b.lo + a.lo * b.hi + a.lo * b.lo);
        add(-(c.hi * d.lo + c.lo * d.hi + c.lo * d.lo));
        return s + err;
    };
    return LVec(det(u[1], w[2], u[2], w[1]), det(u[2], w[0], u[0], w[2]), det(u[0], w[1], u[1], w[0]));
}

/// The two bodies' vertices relative to A's first vertex, and the oracle's answers (file comment).
class LeastOverlap {
public:
    LeastOverlap(const std::vector<Vec3>& a, const std::vector<Vec3>& b) : a_(a), b_(b), ref_(toL(a.at(0))) {
        for (const Vec3& x : a) pa_.push_back(toL(x) - ref_);
        for (const Vec3& x : b) pb_.push_back(toL(x) - ref_);
        for (const std::vector<Vec3>* body : {&a_, &b_}) {
            const std::vector<Vec3>& v = *body;
            for (std::size_t i = 0; i < v.size(); ++i)
                for (std::size_t j = i + 1; j < v.size(); ++j)
                    for (std::size_t k = j + 1; k < v.size(); ++k) consider(cross(edge(v[i], v[j]), edge(v[i], v[k])));
        }
        for (std::size_t i = 0; i < a_.size(); ++i)
            for (std::size_t j = i + 1; j < a_.size(); ++j) {
                const ExactVec ea = edge(a_[i], a_[j]);
                for (std::size_t k = 0; k < b_.size(); ++k)
                    for (std::size_t l = k + 1; l < b_.size(); ++l) consider(cross(ea, edge(b_[k], b_[l])));
            }
    }

    /// D*: the least overlap (> 0: overlapping by it; <= 0: apart or touching, −D* a lower bound of
    /// the distance).
    long double leastOverlap() const { return least_; }
    /// A unit direction attaining D* (from A toward B).
    const LVec& leastAxis() const { return axis_; }

    /// h_{A−B}(n) = h_A(n) + h_B(−n) for unit n (the overlap of the projections on n).
    long double overlapAlong(const LVec& n) const {
        long double maxA = -std::numeric_limits<long double>::infinity(), minB = -maxA;
        for (const LVec& p : pa_) maxA = std::max(maxA, p.dot(n));
        for (const LVec& p : pb_) minB = std::min(minB, p.dot(n));
        return maxA - minB;
    }

    /// The distance of the two bodies (0 when D* > 0), brute force over the feature pairs.
    long double distance() const {
        if (least_ > 0) return 0;
        long double best = std::numeric_limits<long double>::infinity();
        for (const LVec& p : pa_) best = std::min(best, toTriangles(pb_, p));
        for (const LVec& p : pb_) best = std::min(best, toTriangles(pa_, p));
        for (std::size_t i = 0; i < a_.size(); ++i)
            for (std::size_t j = i + 1; j < a_.size(); ++j)
                for (std::size_t k = 0; k < b_.size(); ++k)
                    for (std::size_t l = k + 1; l < b_.size(); ++l) best = std::min(best, segmentPair(i, j, k, l));
        return best;
    }

    /// The signed distance: the distance apart, −D* overlapping.
    long double signedDistance() const { return least_ > 0 ? -least_ : distance(); }

private:
    void consider(const LVec& c) {
        const long double len = c.norm();
        if (!(len > 0)) return;
        const LVec n = c / len;
        const long double forward = overlapAlong(n), backward = overlapAlong(-n);
        if (forward < least_) least_ = forward, axis_ = n;
        if (backward < least_) least_ = backward, axis_ = -n;
    }

    /// The distance from x to the nearest triangle of three points of `body`.
    static long double toTriangles(const std::vector<LVec>& body, const LVec& x) {
        long double best = std::numeric_limits<long double>::infinity();
        for (std::size_t i = 0; i < body.size(); ++i)
            for (std::size_t j = i + 1; j < body.size(); ++j)
                for (std::size_t k = j + 1; k < body.size(); ++k)
                    best = std::min(best, long_double::triangleDistanceL(body[i] - x, body[j] - x, body[k] - x));
        return best;
    }

    /// The distance of segments a_i a_j and b_k b_l: of the origin to P = {p1 + s ea − t eb}, p1 =
    /// a_i − b_k, s, t in [0, 1]. Inside P's plane the origin projects to p1 + s ea − t eb with
    /// s = p1 · (n × eb) / |c|, t = p1 · (n × ea) / |c| (c = ea × eb, n = c / |c|): then |n · p1|;
    /// otherwise the nearest side (a point against a segment). Near a side of a sliver P the two
    /// differ by s |ea| sin(angle), which the rounding of s cannot make large.
    long double segmentPair(std::size_t i, std::size_t j, std::size_t k, std::size_t l) const {
        const LVec p1 = pa_[i] - pb_[k], p2 = pa_[j] - pb_[k], p3 = pa_[j] - pb_[l], p4 = pa_[i] - pb_[l];
        const long double sides = std::min({long_double::segmentDistanceL(p1, p2), long_double::segmentDistanceL(p2, p3),
                                            long_double::segmentDistanceL(p3, p4), long_double::segmentDistanceL(p4, p1)});
        const ExactVec xa = edge(a_[i], a_[j]), xb = edge(b_[k], b_[l]);
        const LVec c = cross(xa, xb);
        const long double len = c.norm();
        if (!(len > 0)) return sides;
        const LVec n = c / len;
        const LVec ea(xa[0].hi + xa[0].lo, xa[1].hi + xa[1].lo, xa[2].hi + xa[2].lo);
        const LVec eb(xb[0].hi + xb[0].lo, xb[1].hi + xb[1].lo, xb[2].hi + xb[2].lo);
        const long double s = p1.dot(n.cross(eb)) / len, t = p1.dot(n.cross(ea)) / len;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1) return std::min(sides, std::abs(n.dot(p1)));
        return sides;
    }

    std::vector<Vec3> a_, b_;
    LVec ref_;
    std::vector<LVec> pa_, pb_;
    long double least_ = std::numeric_limits<long double>::infinity();
    LVec axis_ = LVec::UnitX();
};

}  // namespace cdlab::verification::least_overlap
