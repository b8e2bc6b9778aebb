#include "core/gjk_epa/simplex_solver.h"

#include <algorithm>
#include <cmath>

#include "core/base/accurate_cross.h"
#include "core/base/orient.h"
#include "core/base/tolerances.h"

namespace cdlab {

namespace {

// A triangle (tetrahedron) is treated as lower-dimensional when its doubled area (six-fold volume)
// is below this fraction of the product of its edge lengths: the cross / triple products carry a
// rounding error of a few ulps of that product, so below ~1e-14 their sign and direction are noise.
constexpr double kDegenerate = 1e-14;

void setVertex(SimplexClosest& c, const Vec3* w, int i) {
    c.count = 1;
    c.index[0] = i;
    c.lambda[0] = 1.0;
    c.v = w[i];
}

// ---- Signed volumes (Montanari et al. 2017) -------------------------------------------------

// S1D: segment w[i] w[j], i < j. Barycentric weights from dot products with t = w[j] - w[i]:
// lambda_j = -w[i]·t / t·t, lambda_i = w[j]·t / t·t (both positive iff the origin projects inside).
void s1d(const Vec3* w, int i, int j, SimplexClosest& c) {
    const Vec3& p = w[i];
    const Vec3& q = w[j];
    const Vec3 t = q - p;
    const double tt = t.squaredNorm();
    const double numJ = -p.dot(t);
    const double numI = q.dot(t);
    // Comparison order matters: !(tt > 0) also catches NaN and a zero-length segment.
    if (!(tt > 0.0) || numJ <= 0.0) {  // vertex i region (or repeated point)
        setVertex(c, w, i);
        return;
    }
    if (numI <= 0.0) {  // vertex j region
        setVertex(c, w, j);
        return;
    }
    // edge region: p_closest = w_i + lambda_j t. lambda_j carries an error of ~eps |w| / |t|
    // (cancellation in w_i·t), but it only slides v along the segment, which changes |v| to second
    // order. Taking lambda_i = 1 - lambda_j keeps v on the line; normalizing two separately
    // computed weights would not (it scales v by 1 + O(eps |w| / |t|)).
    //
    // v = w_i + lambda_j t has an error of ~u |w_i| in every direction: when the line passes far
    // closer to the origin than |w| (|v|^2 < 1e-6 |w_i|^2), v's direction is off by ~u |w| / |v| and
    // the next support along -v misses what lies beyond (a segment 1e9 long passing 1e-9 beside the
    // origin lost v's component along t and GJK stopped 0.7 short; the long edge of a sliver face
    // 1e-10 beside the origin missed the face's third point). There v = t x (w_i x w_j) / t·t (the
    // same vector: t x (p x t) = p t·t - t (t·p)) with w_i x w_j from error-free products: the
    // cross of two nearly orthogonal vectors, accurate to a few u in every direction.
    const double lj = numJ / tt;
    c.count = 2;
    c.index[0] = i;
    c.index[1] = j;
    c.lambda[0] = 1.0 - lj;
    c.lambda[1] = lj;
    c.v = p + lj * t;
    if (c.v.squaredNorm() < 1e-6 * std::max(p.squaredNorm(), q.squaredNorm()))
        c.v = t.cross(accurateCross(Vec3::Zero(), p, q)) / tt;
}

void keepNearest(SimplexClosest& best, const SimplexClosest& candidate, bool& have) {
    if (!have || candidate.v.squaredNorm() < best.v.squaredNorm()) {
        best = candidate;
        have = true;
    }
}

// S2D: triangle w[i] w[j] w[k], i < j < k. Project the origin onto the plane (p0), then compare
// the signed areas of the sub-triangles (p0 replacing one vertex) in the coordinate plane where the
// triangle's projection is largest. Same signs: p0 is inside. Otherwise descend into the edges the
// origin lies beyond (their area has the wrong sign).
void s2d(const Vec3* w, int i, int j, int k, SimplexClosest& c) {
    const Vec3& a = w[i];
    const Vec3& b = w[j];
    const Vec3& d = w[k];
    const Vec3 ab = b - a;
    const Vec3 ad = d - a;
    Vec3 n = ab.cross(ad);
    double nn = n.squaredNorm();
    const double scale2 = std::max({ab.squaredNorm(), ad.squaredNorm(), (d - b).squaredNorm()});
    const int edge[3][2] = {{j, k}, {i, k}, {i, j}};  // edge opposite vertex 0, 1, 2
    bool have = false;
    SimplexClosest candidate;
    if (!(nn > kDegenerate * kDegenerate * scale2 * scale2)) {
        // Zero-area triangle (collinear or repeated points): its hull is the union of its edges.
        for (const auto& e : edge) {
            s1d(w, e[0], e[1], candidate);
            keepNearest(c, candidate, have);
        }
        return;
    }
    Vec3 p0 = n * (a.dot(n) / nn);  // projection of the origin onto the plane
    // A plane passing far closer to the origin than its points (|p0|^2 < 1e-6 |w|^2): the plain
    // cross product's direction errs by ~u / sine (the sine of the angle at a), which moves p0 by
    // ~u |w| / sine, comparable to p0 itself on a sliver (GJK stopped on a segment at 55 times the
    // distance) and still 1e-3 of it at a sine of 1e-3 (a stop on "no progress" 26% off). Error-free
    // products (accurateCross) keep the normal to a few u.
    // The weights then come from the same error-free products: the signed areas n·((w_j − p0) x
    // (w_k − p0)) (the projected 2D areas of a sliver lost the witnesses: points 68x the distance
    // apart).
    double cm[3], mu;
    const bool nearOrigin = p0.squaredNorm() < 1e-6 * std::max({a.squaredNorm(), b.squaredNorm(), d.squaredNorm()});
    if (nearOrigin) {
        n = accurateCross(a, b, d);
        nn = n.squaredNorm();
        p0 = n * (a.dot(n) / nn);
        cm[0] = accurateCross(p0, b, d).dot(n);
        cm[1] = accurateCross(p0, d, a).dot(n);
        cm[2] = accurateCross(p0, a, b).dot(n);
        mu = 1.0;
    } else {
        int axis = 0;
        if (std::abs(n[1]) > std::abs(n[axis])) axis = 1;
        if (std::abs(n[2]) > std::abs(n[axis])) axis = 2;
        const int x = (axis + 1) % 3;
        const int y = (axis + 2) % 3;
        auto cross2 = [x, y](const Vec3& u, const Vec3& v) { return u[x] * v[y] - u[y] * v[x]; };
        const Vec3 pa = a - p0;
        const Vec3 pb = b - p0;
        const Vec3 pd = d - p0;
        // C_m = projected area of the triangle with p0 in place of vertex m; mu = n[axis] = sum C_m.
        cm[0] = cross2(pb, pd), cm[1] = cross2(pd, pa), cm[2] = cross2(pa, pb);
        mu = n[axis];
    }
    if (cm[0] * mu > 0.0 && cm[1] * mu > 0.0 && cm[2] * mu > 0.0) {
        // face region: p_closest = p0 = l0 a + l1 b + l2 d
        const double sum = cm[0] + cm[1] + cm[2];
        c.count = 3;
        c.index[0] = i;
        c.index[1] = j;
        c.index[2] = k;
        for (int m = 0; m < 3; ++m) c.lambda[m] = cm[m] / sum;
        // sum lambda_m w_m errs by ~u |w| in every direction, which turns v by ~u |w| / |v|: when
        // the plane passes far closer to the origin than |w| (as for s1d's segments), the support
        // along that -v missed points 1e-9 |w| beyond the face (a flat body with the origin inside
        // it: GJK stopped on a duplicate support, "separated"). There v is p0, along the normal.
        c.v = nearOrigin ? p0 : Vec3(c.lambda[0] * a + c.lambda[1] * b + c.lambda[2] * d);
        return;
    }
    for (int m = 0; m < 3; ++m) {
        if (cm[m] * mu > 0.0) continue;  // origin on the inner side of this edge: not its region
        s1d(w, edge[m][0], edge[m][1], candidate);
        keepNearest(c, candidate, have);
    }
    if (!have) setVertex(c, w, i);  // unreachable unless NaN: keep a defined answer
}

// The sign of a signed volume `value` computed in doubles from vectors of squared lengths l1, l2, l3,
// or 0 when it lies within its rounding band. A triple product x·(y×z) of rounded inputs errs by
// less than ~8 u |x| |y| |z| (the inputs' own rounding, the cross and the dot products); 16 u leaves
// room. Compared squared: no square root; an overflow or underflow of the bound, or a NaN, gives 0.
int clearVolumeSign(double value, double l1, double l2, double l3) {
    constexpr double kBand = 16.0 * kUnitRoundoff;
    if (!(value * value > kBand * kBand * l1 * l2 * l3)) return 0;
    return value > 0.0 ? 1 : -1;
}

// The certain sign of each C_m (below), given its double value and the squared edge lengths
// l1, l2, l3 of e_i = w_i - w_0: the plain sign where it clears its band, else orient3d's exact one.
void facetSigns(const Vec3* w, const double* cm, double l1, double l2, double l3, int* sign) {
    const double l0 = w[0].squaredNorm();
    sign[0] = clearVolumeSign(cm[0], w[1].squaredNorm(), w[2].squaredNorm(), w[3].squaredNorm());
    sign[1] = clearVolumeSign(cm[1], l0, l2, l3);
    sign[2] = clearVolumeSign(cm[2], l0, l3, l1);
    sign[3] = clearVolumeSign(cm[3], l0, l1, l2);
    const Vec3 origin = Vec3::Zero();
    if (sign[0] == 0) sign[0] = orient3d(origin, w[1], w[2], w[3]);
    if (sign[1] == 0) sign[1] = orient3d(w[0], origin, w[2], w[3]);
    if (sign[2] == 0) sign[2] = orient3d(w[0], w[1], origin, w[3]);
    if (sign[3] == 0) sign[3] = orient3d(w[0], w[1], w[2], origin);
}

// S3D: tetrahedron w[0..3]. C_m = signed volume with the origin in place of vertex m, D = sum C_m.
// All C_m of D's sign: the origin is inside. Otherwise descend into the facets it lies beyond.
// The signs decide containment, so each is certain: a C_m within its rounding band (a sliver
// tetrahedron, the origin within ~u |w|^3 / area of a facet's plane) takes the exact sign of
// orient3d (Shewchuk's predicate): a plain sign there put the origin 1e-6 outside a polytope of size
// 1.5e3 inside its terminal sliver, and GJK answered "intersecting".
void s3d(const Vec3* w, SimplexClosest& c) {
    const Vec3 e1 = w[1] - w[0];
    const Vec3 e2 = w[2] - w[0];
    const Vec3 e3 = w[3] - w[0];
    const Vec3 n23 = e2.cross(e3);
    const Vec3 n31 = e3.cross(e1);
    const Vec3 n12 = e1.cross(e2);
    const double det = e1.dot(n23);
    double cm[4];
    cm[1] = -w[0].dot(n23);
    cm[2] = -w[0].dot(n31);
    cm[3] = -w[0].dot(n12);
    cm[0] = w[1].dot(w[2].cross(w[3]));
    const int face[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};  // facet opposite vertex m
    const double l1 = e1.squaredNorm(), l2 = e2.squaredNorm(), l3 = e3.squaredNorm();
    const double edgeProduct = std::sqrt(l1 * l2 * l3);
    bool have = false;
    SimplexClosest candidate;
    // det's sign: plain where it clears 1e-14 of the edge product (far above its 16 u rounding),
    // else orient3d's exact one (a needle tetrahedron, det / edge product ~6e-16, can hold the origin
    // well inside: a threshold called it flat and GJK answered "apart"; an overflowing edge product,
    // edges beyond ~2^170, too). Flat only when exactly flat: then its hull is the union of its facets.
    const int detSign = std::abs(det) > kDegenerate * edgeProduct ? (det > 0.0 ? 1 : -1) : orient3d(w[0], w[1], w[2], w[3]);
    if (detSign == 0) {
        for (const auto& f : face) {
            s2d(w, f[0], f[1], f[2], candidate);
            keepNearest(c, candidate, have);
        }
        return;
    }
    int sign[4];
    facetSigns(w, cm, l1, l2, l3, sign);
    if (sign[0] == detSign && sign[1] == detSign && sign[2] == detSign && sign[3] == detSign) {
        // interior: the origin is inside the tetrahedron, lambda_m = C_m / D (rounded C_m of the
        // right sign: a band's C_m may have rounded to the wrong one, so clamp it at 0)
        c.count = 4;
        c.v.setZero();
        double sum = 0.0;
        for (int m = 0; m < 4; ++m) sum += std::max(cm[m] * detSign, 0.0);
        for (int m = 0; m < 4; ++m) {
            c.index[m] = m;
            c.lambda[m] = sum > 0.0 ? std::max(cm[m] * detSign, 0.0) / sum : 0.25;
            c.v += c.lambda[m] * w[m];
        }
        return;
    }
    for (int m = 0; m < 4; ++m) {
        if (sign[m] == detSign) continue;  // origin on the inner side of this facet
        s2d(w, face[m][0], face[m][1], face[m][2], candidate);
        keepNearest(c, candidate, have);
    }
    if (!have) setVertex(c, w, 0);  // unreachable unless NaN
}

}  // namespace

SimplexClosest closestSignedVolumes(const Vec3* w, int n) {
    SimplexClosest c;
    switch (n) {
        case 1: setVertex(c, w, 0); break;
        case 2: s1d(w, 0, 1, c); break;
        case 3: s2d(w, 0, 1, 2, c); break;
        case 4: s3d(w, c); break;
        default: break;  // count 0: empty simplex, no answer
    }
    return c;
}

// ---- Johnson's distance sub-algorithm (van den Bergen §4.3.3) ---------------------------------

SimplexClosest closestJohnson(const Vec3* y, int n) {
    SimplexClosest c;
    if (n < 1 || n > 4) return c;
    double dp[4][4];
    for (int i = 0; i < n; ++i)
        for (int j = i; j < n; ++j) dp[i][j] = dp[j][i] = y[i].dot(y[j]);
    // delta[X][j]: cofactor of y_j in subset X (bit mask). Recursion:
    //   delta_i({i}) = 1,  delta_j(X + {j}) = sum_{i in X} delta_i(X) (y_i·y_k - y_i·y_j), k in X.
    double delta[16][4] = {};
    const int full = (1 << n) - 1;
    for (int mask = 1; mask <= full; ++mask) {
        for (int j = 0; j < n; ++j) {
            if (!(mask & (1 << j))) continue;
            const int rest = mask & ~(1 << j);
            if (rest == 0) {
                delta[mask][j] = 1.0;
                continue;
            }
            int k = 0;
            while (!(rest & (1 << k))) ++k;
            double s = 0.0;
            for (int i = 0; i < n; ++i)
                if (rest & (1 << i)) s += delta[rest][i] * (dp[i][k] - dp[i][j]);
            delta[mask][j] = s;
        }
    }
    auto build = [&](int mask) {
        SimplexClosest r;
        double sum = 0.0;
        for (int i = 0; i < n; ++i)
            if (mask & (1 << i)) sum += delta[mask][i];
        r.v.setZero();
        for (int i = 0; i < n; ++i) {
            if (!(mask & (1 << i))) continue;
            r.index[r.count] = i;
            r.lambda[r.count] = delta[mask][i] / sum;
            r.v += r.lambda[r.count] * y[i];
            ++r.count;
        }
        return r;
    };
    auto positive = [&](int mask) {
        for (int i = 0; i < n; ++i)
            if ((mask & (1 << i)) && !(delta[mask][i] > 0.0)) return false;
        return true;
    };
    // The answer X: every cofactor in X positive, every extension X + {j} with delta_j <= 0.
    for (int mask = 1; mask <= full; ++mask) {
        if (!positive(mask)) continue;
        bool ok = true;
        for (int j = 0; j < n && ok; ++j)
            if (!(mask & (1 << j)) && delta[mask | (1 << j)][j] > 0.0) ok = false;
        if (!ok) continue;
        // "Inside the tetrahedron" ends GJK with an intersection: decided by the certain signs of
        // the signed volumes (S3D's), not by cofactors of rounded dot products.
        if (mask == 15) {
            SimplexClosest sv;
            s3d(y, sv);
            if (sv.count != 4) return sv;
        }
        return build(mask);
    }
    // Backup procedure: rounding broke the region test; take the sub-simplex with all-positive
    // cofactors whose closest point is nearest (singletons always qualify).
    bool have = false;
    for (int mask = 1; mask <= full; ++mask) {
        if (!positive(mask)) continue;
        keepNearest(c, build(mask), have);
    }
    return c;
}

const char* nameOf(SimplexSolver solver) { return solver == SimplexSolver::Johnson ? "Johnson" : "SignedVolumes"; }

}  // namespace cdlab
