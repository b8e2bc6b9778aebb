#include "core/base/accurate_cross.h"

#include "core/base/double_double.h"

namespace cdlab {

namespace {

// (u_hi + u_lo) * (v_hi + v_lo) - (w_hi + w_lo) * (z_hi + z_lo) with a compensated sum.
double crossTerm(double uh, double ul, double vh, double vl, double wh, double wl, double zh, double zl) {
    double p1, e1, p2, e2;
    dd::twoProduct(uh, vh, p1, e1);
    dd::twoProduct(wh, zh, p2, e2);
    const double terms[8] = {p1, -p2, e1, -e2, uh * vl, ul * vh, -(wh * zl), -(wl * zh)};
    double s = 0.0, comp = 0.0;
    for (double t : terms) {
        double err;
        dd::twoSum(s, t, s, err);
        comp += err;
    }
    return s + comp + (ul * vl - wl * zl);
}

}  // namespace

Vec3 accurateCross(const Vec3& a, const Vec3& b, const Vec3& c) {
    double uh[3], ul[3], vh[3], vl[3];  // u = b - a, v = c - a, each exactly as hi + lo
    for (int k = 0; k < 3; ++k) {
        dd::twoSum(b[k], -a[k], uh[k], ul[k]);
        dd::twoSum(c[k], -a[k], vh[k], vl[k]);
    }
    return Vec3(crossTerm(uh[1], ul[1], vh[2], vl[2], uh[2], ul[2], vh[1], vl[1]),
                crossTerm(uh[2], ul[2], vh[0], vl[0], uh[0], ul[0], vh[2], vl[2]),
                crossTerm(uh[0], ul[0], vh[1], vl[1], uh[1], ul[1], vh[0], vl[0]));
}

Vec3 accurateOffsetCross(const Vec3& a, const Vec3& b, const Vec3& v) {
    double uh[3], ul[3];  // u = b - a exactly as hi + lo; v is exact with lo = 0
    for (int k = 0; k < 3; ++k) dd::twoSum(b[k], -a[k], uh[k], ul[k]);
    return Vec3(crossTerm(uh[1], ul[1], v[2], 0.0, uh[2], ul[2], v[1], 0.0),
                crossTerm(uh[2], ul[2], v[0], 0.0, uh[0], ul[0], v[2], 0.0),
                crossTerm(uh[0], ul[0], v[1], 0.0, uh[1], ul[1], v[0], 0.0));
}

}  // namespace cdlab
