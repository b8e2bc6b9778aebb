#include "core/bounding/bounding_sphere.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <list>
#include <numbers>
#include <random>

#include <Eigen/Dense>

#include "core/base/tolerances.h"

namespace cdlab {

namespace {

// A point counts as outside the current ball when |p - c|^2 > r^2 (1 + kOutsideRel). WHY: the
// support points of a computed ball lie on its boundary only to rounding (relative ~1e-15 for a
// well-shaped support set, more for the thin ones we still accept); a looser test would push a
// point that is on the boundary already. The final radius is max |p - c| anyway, so this only
// decides which points join the support set, never containment.
constexpr double kOutsideRel = 1e-12;

// A support set whose normalized Gram determinant det(G) / prod(G_ii) (the product of squared
// sines of the "angles" of the simplex it spans: 1 for orthogonal edges, 0 for affinely
// dependent points) is below this is rejected as affinely dependent. WHY: the circumcenter's
// relative error grows like eps / det; at 1e-10 it stays ~1e-6 of the radius, while exactly
// collinear / coplanar / repeated points (det 0 up to rounding, ~1e-16) are rejected.
constexpr double kDependentDet = 1e-10;

// Finite points relative to ref = the center of their bounding box (large offsets cancel in
// the subtraction, exactly when the points are clustered: Sterbenz), with their input indices.
struct LocalPoints {
    Vec3 ref = Vec3::Zero();
    std::vector<Vec3> p;
    std::vector<int> index;
    int skipped = 0;
};

LocalPoints localize(std::span<const Vec3> points) {
    LocalPoints out;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : points) {
        if (!p.allFinite()) continue;
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    out.ref = 0.5 * (lo + hi);
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
        if (!points[i].allFinite()) {
            ++out.skipped;
            continue;
        }
        out.p.push_back(points[i] - out.ref);
        out.index.push_back(i);
    }
    return out;
}

Sphere emptySphere() { return Sphere{Vec3::Constant(kNaN), -1.0}; }

// World sphere from a local center: radius = max distance to the points (containment), padded
// by the rounding of ref + center (half an ulp per coordinate, sqrt(3) over the three) and of
// the distance itself (a few eps relative). 4 eps covers both.
Sphere finish(const LocalPoints& lp, const Vec3& center) {
    double r2 = 0.0;
    for (const Vec3& p : lp.p) r2 = std::max(r2, (p - center).squaredNorm());
    const double r = std::sqrt(r2);
    // center == 0: ref + center is ref exactly, nothing to pad (a single point keeps radius 0).
    const double magnitude = center.isZero(0.0) ? 0.0 : lp.ref.cwiseAbs().maxCoeff() + center.cwiseAbs().maxCoeff();
    return Sphere{lp.ref + center, r * (1.0 + 4.0 * kMachineEpsilon) + 4.0 * kMachineEpsilon * magnitude};
}

// Smallest ball with every support point on its boundary: its center lies in their affine hull,
// c = q0 + sum_i l_i v_i with v_i = q_i - q0, and |c - q_i| = |c - q0| gives the Gram system
// sum_j (v_i . v_j) l_j = |v_i|^2 / 2. Returns false for a (nearly) affinely dependent set.
bool supportBall(const std::vector<Vec3>& q, Vec3& center, double& r2) {
    const int k = static_cast<int>(q.size()) - 1;
    if (k == 0) {
        center = q[0];
        r2 = 0.0;
        return true;
    }
    Eigen::MatrixXd gram(k, k);
    Eigen::VectorXd rhs(k);
    std::vector<Vec3> v;
    for (int i = 0; i < k; ++i) v.push_back(q[i + 1] - q[0]);
    double diagonalProduct = 1.0;
    for (int i = 0; i < k; ++i) {
        for (int j = 0; j < k; ++j) gram(i, j) = v[i].dot(v[j]);
        rhs[i] = 0.5 * gram(i, i);
        diagonalProduct *= gram(i, i);
    }
    if (!(diagonalProduct > 0.0)) return false;  // a repeated point
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(gram);
    if (!(lu.determinant() / diagonalProduct > kDependentDet)) return false;
    const Eigen::VectorXd l = lu.solve(rhs);
    center = q[0];
    for (int i = 0; i < k; ++i) center += l[i] * v[i];
    r2 = 0.0;
    for (const Vec3& p : q) r2 = std::max(r2, (p - center).squaredNorm());
    return center.allFinite();
}

// Gärtner's move-to-front Welzl. The current ball (center, r2) is NOT popped with the support
// set: after a recursive call returns, the ball is the one found for the prefix, which is the
// invariant the loop needs (ball = mb(points before the scan position, support)).
struct MoveToFront {
    const LocalPoints& lp;
    std::list<int> order;
    std::vector<int> support;      // local indices
    std::vector<int> ballSupport;  // support of the current ball
    Vec3 center = Vec3::Zero();
    double r2 = -1.0;  // empty ball: every point is outside
    WelzlTrace* trace = nullptr;

    bool outside(const Vec3& p) const { return (p - center).squaredNorm() > r2 + kOutsideRel * std::max(r2, 0.0); }

    bool push(int i) {
        std::vector<Vec3> q;
        for (int s : support) q.push_back(lp.p[s]);
        q.push_back(lp.p[i]);
        Vec3 c;
        double rr = 0.0;
        const bool ok = supportBall(q, c, rr);
        if (trace) {
            WelzlStep step;
            step.pointIndex = lp.index[i];
            step.depth = static_cast<int>(support.size());
            for (int s : support) step.support.push_back(lp.index[s]);
            step.support.push_back(lp.index[i]);
            step.accepted = ok;
            step.ball = ok ? Sphere{lp.ref + c, std::sqrt(rr)} : Sphere{lp.ref + center, std::sqrt(std::max(r2, 0.0))};
            trace->steps.push_back(step);
        }
        if (!ok) return false;
        support.push_back(i);
        ballSupport = support;
        center = c;
        r2 = rr;
        return true;
    }

    void run(std::list<int>::iterator end) {
        if (support.size() == 4) return;  // four points on the boundary fix the ball in 3D
        for (auto k = order.begin(); k != end;) {
            auto j = k++;
            if (!outside(lp.p[*j])) continue;
            if (!push(*j)) continue;  // dependent support set: leave the point to the final radius
            run(j);
            support.pop_back();
            order.splice(order.begin(), order, j);  // move to front
        }
    }
};

}  // namespace

const char* nameOf(WelzlStatus status) {
    switch (status) {
        case WelzlStatus::Exact: return "Exact";
        case WelzlStatus::Approximate: return "Approximate";
        case WelzlStatus::Empty: return "Empty";
    }
    return "?";
}

Sphere fitSphereRitter(std::span<const Vec3> points, RitterTrace* trace) {
    if (trace) *trace = RitterTrace{};
    const LocalPoints lp = localize(points);
    if (trace) trace->skippedNonFinite = lp.skipped;
    const int n = static_cast<int>(lp.p.size());
    if (n == 0) return emptySphere();
    // Ericson §4.3.2 MostSeparatedPointsOnAABB: the min / max point on each axis, the pair with
    // the largest squared distance.
    int bestA = 0, bestB = 0;
    double bestD2 = -1.0;
    for (int axis = 0; axis < 3; ++axis) {
        int lo = 0, hi = 0;
        for (int i = 1; i < n; ++i) {
            if (lp.p[i][axis] < lp.p[lo][axis]) lo = i;
            if (lp.p[i][axis] > lp.p[hi][axis]) hi = i;
        }
        const double d2 = (lp.p[hi] - lp.p[lo]).squaredNorm();
        if (d2 > bestD2) {
            bestD2 = d2;
            bestA = lo;
            bestB = hi;
        }
    }
    Vec3 c = 0.5 * (lp.p[bestA] + lp.p[bestB]);
    double r = (lp.p[bestB] - c).norm();
    if (trace) {
        trace->initialPair = {lp.index[bestA], lp.index[bestB]};
        trace->initial = Sphere{lp.ref + c, r};
    }
    // Ericson §4.3.2 SphereOfSphereAndPt: a point at distance d > r outside pulls the sphere to
    // radius (r + d) / 2, the center moving (d - r) / 2 toward it (the opposite side stays put).
    for (int i = 0; i < n; ++i) {
        const Vec3 d = lp.p[i] - c;
        const double d2 = d.squaredNorm();
        if (!(d2 > r * r)) continue;
        const double dist = std::sqrt(d2);
        const double newR = 0.5 * (r + dist);
        // Invariant: a recorded grow step increases the radius. A point outside by less than the
        // rounding of sqrt and of the mean (d2 > r² but newR == r) leaves the sphere as it is
        // (the centre would move by 0 · d): it is not a step, so the trace counts only real growth
        // (tests/core/bounding/bounding_sphere_test.cpp, "Ritter: every grow step grows").
        if (!(newR > r)) continue;
        const Sphere before{lp.ref + c, r};
        c += ((newR - r) / dist) * d;
        r = newR;
        if (trace) trace->steps.push_back({lp.index[i], before, Sphere{lp.ref + c, r}});
    }
    return finish(lp, c);
}

Sphere fitSphereWelzl(std::span<const Vec3> points, WelzlTrace* trace) {
    if (trace) *trace = WelzlTrace{};
    const LocalPoints lp = localize(points);
    if (trace) trace->skippedNonFinite = lp.skipped;
    const int n = static_cast<int>(lp.p.size());
    if (n == 0) return emptySphere();
    // Fixed-seed shuffle: Welzl's expected O(n) needs a random order; a constant seed keeps the
    // result (and the trace) reproducible for the same input.
    std::vector<int> perm(n);
    for (int i = 0; i < n; ++i) perm[i] = i;
    std::mt19937 rng(0x5eed);
    for (int i = n - 1; i > 0; --i) std::swap(perm[i], perm[std::uniform_int_distribution<int>(0, i)(rng)]);
    MoveToFront mtf{lp, std::list<int>(perm.begin(), perm.end()), {}, {}, Vec3::Zero(), -1.0, trace};
    mtf.run(mtf.order.end());
    const Sphere ball = finish(lp, mtf.center);
    if (trace) {
        for (int s : mtf.ballSupport) trace->finalSupport.push_back(lp.index[s]);
        const double supportR = std::sqrt(std::max(mtf.r2, 0.0));
        double maxR2 = 0.0;
        for (const Vec3& p : lp.p) maxR2 = std::max(maxR2, (p - mtf.center).squaredNorm());
        trace->status =
            std::sqrt(maxR2) > supportR * (1.0 + kWelzlExactRelative) ? WelzlStatus::Approximate : WelzlStatus::Exact;
    }
    return ball;
}

double volume(const Sphere& sphere) {
    if (std::isnan(sphere.radius)) return kNaN;
    if (sphere.radius < 0.0) return 0.0;
    return 4.0 / 3.0 * std::numbers::pi * sphere.radius * sphere.radius * sphere.radius;
}

}  // namespace cdlab
