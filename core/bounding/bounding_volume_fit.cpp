#include "core/bounding/bounding_volume_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/base/tolerances.h"

namespace cdlab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A triangle whose |e1 x e2| is below this fraction of |e1| |e2| (sine of its angle < 1e-12)
// has an area that is rounding noise of the cross product (about a few eps |e1| |e2|), so its
// weight in the continuous covariance would be noise too: it counts as zero-area.
constexpr double kSliverSine = 1e-12;

// Pad added to every OBB half extent, in units of eps times the magnitude of the numbers
// involved (|ref|_inf + the largest |projection|). WHY: the extents come from projections
// u = A^T (p - ref) and the center is ref + A (lo + hi) / 2; each of these roundings is a few
// eps of those magnitudes, and A is orthonormal only to a few eps. 16 eps covers all of them,
// so that contains(box, p) holds for every input point when evaluated in double, while the box
// grows by a relative 1e-15 only (invisible in any tightness measure).
constexpr double kExtentPadUlps = 16.0;

Aabb emptyAabb() { return Aabb{Vec3::Constant(kInf), Vec3::Constant(-kInf)}; }

void grow(Aabb& box, const Vec3& p) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
}

bool isEmpty(const Aabb& box) { return !(box.min.array() <= box.max.array()).all(); }

Obb emptyObb() { return Obb{Vec3::Constant(kNaN), Vec3::Zero(), Mat3::Identity()}; }

// Orthonormal right-handed axes from the eigenvectors of a symmetric covariance: columns by
// descending eigenvalue. Gram-Schmidt on the two major vectors and a cross product for the
// third, so that a repeated eigenvalue (where any basis of the eigenspace is an answer) still
// yields a rotation matrix.
Mat3 principalAxes(const Mat3& covariance, Vec3& eigenvaluesDescending) {
    Eigen::SelfAdjointEigenSolver<Mat3> solver(covariance);
    if (solver.info() != Eigen::Success || !solver.eigenvectors().allFinite()) {
        eigenvaluesDescending = covariance.diagonal();
        return Mat3::Identity();
    }
    // Eigen sorts ascending.
    const Vec3 ascending = solver.eigenvalues();
    eigenvaluesDescending = Vec3(ascending[2], ascending[1], ascending[0]);
    Vec3 major = solver.eigenvectors().col(2).normalized();
    Vec3 middle = solver.eigenvectors().col(1);
    middle -= major.dot(middle) * major;
    if (!(middle.norm() > 0.5)) {
        // Cannot happen for an orthonormal eigenvector matrix; kept so a failed solve never
        // gives a singular frame: any unit vector orthogonal to major.
        middle = major.unitOrthogonal();
    }
    middle.normalize();
    Mat3 axes;
    axes.col(0) = major;
    axes.col(1) = middle;
    axes.col(2) = major.cross(middle).normalized();
    return axes;
}

// Box with the given axes holding every point: extents from the projections (relative to ref,
// a point near the data, so that large offsets cancel before the products).
template <class ForEachPoint>
Obb boxFromAxes(const Mat3& axes, const Vec3& ref, ForEachPoint forEachPoint) {
    Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
    forEachPoint([&](const Vec3& p) {
        const Vec3 u = axes.transpose() * (p - ref);
        lo = lo.cwiseMin(u);
        hi = hi.cwiseMax(u);
    });
    const Vec3 mid = 0.5 * (lo + hi);
    Obb box;
    box.axes = axes;
    box.center = ref + axes * mid;
    const double magnitude = ref.cwiseAbs().maxCoeff() + std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    box.halfExtents = (0.5 * (hi - lo)).array() + kExtentPadUlps * kMachineEpsilon * magnitude;
    return box;
}

// The box along the principal axes of `covariance`, the covariance of the points about
// ref + meanLocal; records what it used in the trace.
template <class ForEachPoint>
Obb boxFromCovariance(ObbFitMethod method, const Mat3& covariance, const Vec3& ref, const Vec3& meanLocal,
                      ForEachPoint forEachPoint, ObbFitTrace* trace) {
    Vec3 eigenvalues;
    const Mat3 axes = principalAxes(covariance, eigenvalues);
    if (trace) {
        trace->method = method;
        trace->mean = ref + meanLocal;
        trace->covariance = covariance;
        trace->eigenvalues = eigenvalues;
    }
    return boxFromAxes(axes, ref, forEachPoint);
}

// Point-covariance OBB over the finite points delivered by forEachPoint (count n, bounds box).
template <class ForEachPoint>
Obb pointCovarianceObb(const Aabb& bounds, int n, ForEachPoint forEachPoint, ObbFitTrace* trace) {
    const Vec3 ref = 0.5 * (bounds.min + bounds.max);
    if ((bounds.min.array() == bounds.max.array()).all()) {
        // Every point coincides: no direction is preferred.
        if (trace) {
            trace->method = ObbFitMethod::AxisAligned;
            trace->mean = ref;
            trace->covariance.setZero();
            trace->eigenvalues.setZero();
        }
        return boxFromAxes(Mat3::Identity(), ref, forEachPoint);
    }
    // Mean and covariance of p - ref (two passes: the centered form avoids the cancellation of
    // E[p p^T] - m m^T).
    Vec3 sum = Vec3::Zero();
    forEachPoint([&](const Vec3& p) { sum += p - ref; });
    const Vec3 meanLocal = sum / n;
    Mat3 covariance = Mat3::Zero();
    forEachPoint([&](const Vec3& p) {
        const Vec3 d = p - ref - meanLocal;
        covariance += d * d.transpose();
    });
    covariance /= n;
    return boxFromCovariance(ObbFitMethod::PointCovariance, covariance, ref, meanLocal, forEachPoint, trace);
}

}  // namespace

const char* nameOf(ObbFitMethod method) {
    switch (method) {
        case ObbFitMethod::TriangleCovariance: return "TriangleCovariance";
        case ObbFitMethod::PointCovariance: return "PointCovariance";
        case ObbFitMethod::AxisAligned: return "AxisAligned";
        case ObbFitMethod::Empty: return "Empty";
    }
    return "?";
}

Aabb fitAabb(std::span<const Vec3> points) {
    Aabb box = emptyAabb();
    for (const Vec3& p : points)
        if (p.allFinite()) grow(box, p);
    return box;
}

Aabb transformAabb(const Aabb& box, const Transform& pose) {
    if (!(box.min.x() <= box.max.x() && box.min.y() <= box.max.y() && box.min.z() <= box.max.z())) return box;
    const Mat3 R = pose.rotation.toRotationMatrix();
    const Vec3 c = pose.rotation * (0.5 * (box.min + box.max)) + pose.position;
    const Vec3 h = R.cwiseAbs() * (0.5 * (box.max - box.min));
    return Aabb{c - h, c + h};
}

Aabb fitAabb(std::span<const Triangle> triangles) {
    Aabb box = emptyAabb();
    for (const Triangle& t : triangles) {
        if (!t.allFinite()) continue;
        grow(box, t.a);
        grow(box, t.b);
        grow(box, t.c);
    }
    return box;
}

Obb fitObbCovariance(std::span<const Vec3> points, ObbFitTrace* trace) {
    if (trace) *trace = ObbFitTrace{};
    Aabb bounds = emptyAabb();
    int n = 0;
    for (const Vec3& p : points) {
        if (p.allFinite()) {
            grow(bounds, p);
            ++n;
        } else if (trace) {
            ++trace->skippedNonFinite;
        }
    }
    if (n == 0) return emptyObb();
    auto forEach = [&](auto&& f) {
        for (const Vec3& p : points)
            if (p.allFinite()) f(p);
    };
    return pointCovarianceObb(bounds, n, forEach, trace);
}

Obb fitObbTriangles(std::span<const Triangle> triangles, ObbFitTrace* trace) {
    if (trace) *trace = ObbFitTrace{};
    const Aabb bounds = fitAabb(triangles);
    if (trace)
        for (const Triangle& t : triangles)
            if (!t.allFinite()) ++trace->skippedNonFinite;
    if (isEmpty(bounds)) return emptyObb();
    const Vec3 ref = 0.5 * (bounds.min + bounds.max);
    auto forEachVertex = [&](auto&& f) {
        for (const Triangle& t : triangles) {
            if (!t.allFinite()) continue;
            f(t.a);
            f(t.b);
            f(t.c);
        }
    };

    // Gottschalk et al. 1996 §4 / Ericson §4.4.3, in coordinates relative to ref: the second
    // moment of a uniform mass on triangle (p, q, r) with centroid c and area A is
    //   A / 12 (9 c c^T + p p^T + q q^T + r r^T).
    double totalArea = 0.0;
    Vec3 firstMoment = Vec3::Zero();
    Mat3 secondMoment = Mat3::Zero();
    for (const Triangle& t : triangles) {
        if (!t.allFinite()) continue;
        const Vec3 p = t.a - ref, q = t.b - ref, r = t.c - ref;
        const Vec3 e1 = q - p, e2 = r - p;
        const double crossNorm = e1.cross(e2).norm();
        if (!(crossNorm > kSliverSine * e1.norm() * e2.norm())) continue;  // zero-area: no weight
        const double area = 0.5 * crossNorm;
        const Vec3 c = (p + q + r) / 3.0;
        totalArea += area;
        firstMoment += area * c;
        secondMoment +=
            (area / 12.0) * (9.0 * c * c.transpose() + p * p.transpose() + q * q.transpose() + r * r.transpose());
    }
    if (!(totalArea > 0.0)) {
        // Every triangle has zero area: fall back to the covariance of the vertices.
        int n = 0;
        forEachVertex([&](const Vec3&) { ++n; });
        return pointCovarianceObb(bounds, n, forEachVertex, trace);
    }
    const Vec3 meanLocal = firstMoment / totalArea;
    Mat3 covariance = secondMoment / totalArea - meanLocal * meanLocal.transpose();
    covariance = 0.5 * (covariance + covariance.transpose()).eval();  // exact symmetry
    if (trace) trace->totalArea = totalArea;
    return boxFromCovariance(ObbFitMethod::TriangleCovariance, covariance, ref, meanLocal, forEachVertex, trace);
}

double volume(const Aabb& box) {
    const Vec3 size = box.max - box.min;
    if (size.hasNaN()) return kNaN;
    if ((size.array() <= 0.0).any()) return 0.0;
    return size.x() * size.y() * size.z();
}

double volume(const Obb& box) {
    const Vec3& h = box.halfExtents;
    if (h.hasNaN()) return kNaN;
    if ((h.array() < 0.0).any()) return 0.0;
    return 8.0 * h.x() * h.y() * h.z();
}

bool contains(const Obb& box, const Vec3& p, double slack) {
    const Vec3 u = box.axes.transpose() * (p - box.center);
    return (u.cwiseAbs().array() <= box.halfExtents.array() + slack).all();
}

bool contains(const Aabb& box, const Vec3& p, double slack) {
    return (p.array() >= box.min.array() - slack).all() && (p.array() <= box.max.array() + slack).all();
}

}  // namespace cdlab
