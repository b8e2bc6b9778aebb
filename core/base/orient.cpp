#include "core/base/orient.h"

#include <cmath>

namespace cdlab {

namespace {

// Shewchuk's epsilon: half an ulp of 1 (2^-53 for doubles).
constexpr double kEps = 0x1p-53;
// A-priori relative error bounds of the plain double evaluation (Shewchuk 1997, §4.3,
// ccwerrboundA and o3derrboundA): |det_computed - det_exact| <= bound * permanent.
constexpr double kOrient2dBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEps) * kEps;

// a + b = s + e exactly (Knuth's TwoSum; no precondition on magnitudes).
inline void twoSum(double a, double b, double& s, double& e) {
    s = a + b;
    const double bv = s - a;
    const double av = s - bv;
    e = (a - av) + (b - bv);
}

// a * b = p + e exactly; the fma computes the rounding error of the product exactly.
inline void twoProduct(double a, double b, double& p, double& e) {
    p = a * b;
    e = std::fma(a, b, -p);
}

// A sum of doubles kept exactly as a nonoverlapping expansion, ordered by increasing
// magnitude (Shewchuk's Grow-Expansion with zero elimination).
class ExactSum {
public:
    void add(double b) {
        double q = b;
        int k = 0;
        for (int i = 0; i < n_; ++i) {
            double s, e;
            twoSum(q, c_[i], s, e);
            if (e != 0.0) c_[k++] = e;
            q = s;
        }
        if (q != 0.0) c_[k++] = q;
        n_ = k;
    }
    // x * y * z added exactly: x*y = p + e, then p*z and e*z each split again (4 terms).
    void addProduct3(double sign, double x, double y, double z) {
        double p, e;
        twoProduct(x, y, p, e);
        double p1, e1, p2, e2;
        twoProduct(p, z, p1, e1);
        twoProduct(e, z, p2, e2);
        add(sign * p1);
        add(sign * e1);
        add(sign * p2);
        add(sign * e2);
    }
    void addProduct2(double sign, double x, double y) {
        double p, e;
        twoProduct(x, y, p, e);
        add(sign * p);
        add(sign * e);
    }
    // The largest component carries the sign of a nonoverlapping expansion.
    int sign() const { return n_ == 0 ? 0 : (c_[n_ - 1] > 0.0 ? 1 : -1); }

private:
    // Each add grows the expansion by at most one; 8 * 6 * 4 = 192 terms at most.
    double c_[200];
    int n_ = 0;
};

// Exact det[w0; w1; w2] added with the given sign: the six permutation products.
void addDet3(ExactSum& sum, double sign, const Vec3& w0, const Vec3& w1, const Vec3& w2) {
    static constexpr int kPerm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                        {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    for (int p = 0; p < 6; ++p) {
        const double s = p < 3 ? sign : -sign;
        sum.addProduct3(s, w0[kPerm[p][0]], w1[kPerm[p][1]], w2[kPerm[p][2]]);
    }
}

int signDet3Exact(const Vec3* u, const Vec3* v) {
    // det is multilinear in the rows: det[u0-v0; u1-v1; u2-v2] = sum over the 8 choices of
    // u_i or -v_i per row.
    ExactSum sum;
    for (int mask = 0; mask < 8; ++mask) {
        const Vec3* rows[3];
        double sign = 1.0;
        bool zero = false;
        for (int i = 0; i < 3; ++i) {
            if (mask & (1 << i)) {
                rows[i] = &v[i];
                sign = -sign;
            } else {
                rows[i] = &u[i];
            }
            if (rows[i]->isZero(0.0)) zero = true;
        }
        if (!zero) addDet3(sum, sign, *rows[0], *rows[1], *rows[2]);
    }
    return sum.sign();
}

}  // namespace

int signDet3(const Vec3& u1, const Vec3& v1, const Vec3& u2, const Vec3& v2, const Vec3& u3,
             const Vec3& v3) {
    // Filter: Shewchuk's orient3d evaluation order, expanded along the z column.
    const Vec3 a = u1 - v1, b = u2 - v2, c = u3 - v3;
    const double bxcy = b.x() * c.y(), cxby = c.x() * b.y();
    const double cxay = c.x() * a.y(), axcy = a.x() * c.y();
    const double axby = a.x() * b.y(), bxay = b.x() * a.y();
    const double det = a.z() * (bxcy - cxby) + b.z() * (cxay - axcy) + c.z() * (axby - bxay);
    const double permanent = (std::abs(bxcy) + std::abs(cxby)) * std::abs(a.z()) +
                             (std::abs(cxay) + std::abs(axcy)) * std::abs(b.z()) +
                             (std::abs(axby) + std::abs(bxay)) * std::abs(c.z());
    // Comparison order matters: a NaN det or permanent fails both tests and falls through.
    const double bound = kOrient3dBound * permanent;
    if (det > bound) return 1;
    if (-det > bound) return -1;
    if (!std::isfinite(det) || !std::isfinite(permanent)) return 0;
    if (permanent == 0.0) return 0;  // every product is zero: the determinant is exactly 0
    const Vec3 u[3] = {u1, u2, u3}, v[3] = {v1, v2, v3};
    return signDet3Exact(u, v);
}

int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return signDet3(b, a, c, a, d, a);
}

int orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
    const double left = (b.x() - a.x()) * (c.y() - a.y());
    const double right = (b.y() - a.y()) * (c.x() - a.x());
    const double det = left - right;
    const double detSum = std::abs(left) + std::abs(right);
    const double bound = kOrient2dBound * detSum;
    if (det > bound) return 1;
    if (-det > bound) return -1;
    if (!std::isfinite(det) || !std::isfinite(detSum)) return 0;
    if (detSum == 0.0) return 0;
    // det[b - a; c - a] = det(b, c) - det(b, a) - det(a, c) + det(a, a), with
    // det(p, q) = p.x q.y - p.y q.x.
    ExactSum sum;
    sum.addProduct2(1.0, b.x(), c.y());
    sum.addProduct2(-1.0, b.y(), c.x());
    sum.addProduct2(1.0, a.x(), b.y());
    sum.addProduct2(-1.0, a.y(), b.x());
    sum.addProduct2(-1.0, a.x(), c.y());
    sum.addProduct2(1.0, a.y(), c.x());
    return sum.sign();
}

int dominantAxis(const Vec3& n) {
    const Vec3 m = n.cwiseAbs();
    if (m.x() >= m.y() && m.x() >= m.z()) return 0;
    return m.y() >= m.z() ? 1 : 2;
}

Vec2 dropAxis(const Vec3& p, int axis) {
    return Vec2(p[(axis + 1) % 3], p[(axis + 2) % 3]);
}

int projectionAxis(const Triangle& t) {
    const int first = dominantAxis((t.b - t.a).cross(t.c - t.a));
    for (int k = 0; k < 3; ++k) {
        const int axis = (first + k) % 3;
        if (orient2d(dropAxis(t.a, axis), dropAxis(t.b, axis), dropAxis(t.c, axis)) != 0)
            return axis;
    }
    return -1;
}

}  // namespace cdlab
