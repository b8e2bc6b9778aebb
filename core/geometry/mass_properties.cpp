#include "core/geometry/mass_properties.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "core/base/tolerances.h"

namespace cdlab {

namespace {

// %g: a volume of 1e-20 is not "0.000000".
std::string volumeText(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

}  // namespace

const char* nameOf(MassStatus status) {
    switch (status) {
        case MassStatus::Ok: return "Ok";
        case MassStatus::NonFinite: return "NonFinite";
        case MassStatus::NonPositiveDensity: return "NonPositiveDensity";
        case MassStatus::BadFace: return "BadFace";
        case MassStatus::OpenSurface: return "OpenSurface";
        case MassStatus::NonPlanarFace: return "NonPlanarFace";
        case MassStatus::Degenerate: return "Degenerate";
    }
    return "?";
}

namespace {

MassProperties fail(MassStatus status, int index, std::string message) {
    MassProperties m;
    m.status = status;
    m.index = index;
    m.message = std::move(message);
    return m;
}

}  // namespace

MassProperties computeMassProperties(const std::vector<Vec3>& positions, const std::vector<std::vector<int>>& faces,
                                     const MassPropertiesOptions& options) {
    const double density = options.density;
    if (!std::isfinite(density)) return fail(MassStatus::NonFinite, -1, "density is not finite");
    if (!(density > 0)) return fail(MassStatus::NonPositiveDensity, -1, "density must be > 0");
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (!positions[i].allFinite())
            return fail(MassStatus::NonFinite, static_cast<int>(i), "vertex " + std::to_string(i) + " is not finite");
    if (positions.empty() || faces.size() < 4) return fail(MassStatus::Degenerate, -1, "fewer than 4 faces: no volume");

    // Faces: indices in range, >= 3 vertices; collect directed edges for the closedness check.
    const int n = static_cast<int>(positions.size());
    std::vector<std::pair<int, int>> directed;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& face = faces[f];
        if (face.size() < 3)
            return fail(MassStatus::BadFace, static_cast<int>(f),
                        "face " + std::to_string(f) + " has fewer than 3 vertices");
        for (std::size_t k = 0; k < face.size(); ++k) {
            if (face[k] < 0 || face[k] >= n)
                return fail(MassStatus::BadFace, static_cast<int>(f),
                            "face " + std::to_string(f) + " has a vertex index out of range");
            directed.emplace_back(face[k], face[(k + 1) % face.size()]);
        }
    }
    // Closed and consistently oriented: every directed edge once, and its reverse once.
    std::sort(directed.begin(), directed.end());
    for (std::size_t i = 0; i < directed.size(); ++i) {
        const auto e = directed[i];
        if (i + 1 < directed.size() && directed[i + 1] == e)
            return fail(MassStatus::OpenSurface, -1,
                        "directed edge " + std::to_string(e.first) + "->" + std::to_string(e.second) +
                            " is used twice (faces not consistently oriented)");
        if (!std::binary_search(directed.begin(), directed.end(), std::make_pair(e.second, e.first)))
            return fail(MassStatus::OpenSurface, -1,
                        "edge " + std::to_string(e.first) + "->" + std::to_string(e.second) +
                            " has no opposite: the surface is not closed");
    }

    // Reference point r: the vertex mean (keeps every term O(size), not O(offset)).
    Vec3 r = Vec3::Zero();
    Vec3 lo = positions[0], hi = positions[0];
    for (const Vec3& p : positions) {
        r += p;
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    r /= static_cast<double>(n);
    const double diagonal = (hi - lo).norm();
    const double maxCoord = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    // See MassPropertiesOptions::planarTolerance; the second term is the rounding of coordinates of
    // magnitude maxCoord (a few ulps each) so that far-away solids are not called non-planar.
    const double planeTol = options.planarTolerance * diagonal + ulps(64.0, maxCoord);

    double six = 0.0;            // Σ D      = 6 V
    Vec3 first = Vec3::Zero();   // Σ D (a+b+c) = 24 ∫x
    Mat3 second = Mat3::Zero();  // Σ D (aaᵀ+bbᵀ+ccᵀ+ssᵀ) = 120 ∫xxᵀ
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& face = faces[f];
        // Planarity against the Newell plane (area vector; Newell's method, see Sutherland et al. 1974).
        Vec3 normal = Vec3::Zero();
        Vec3 mean = Vec3::Zero();
        for (std::size_t k = 0; k < face.size(); ++k) {
            const Vec3 p = positions[face[k]] - r, q = positions[face[(k + 1) % face.size()]] - r;
            normal += p.cross(q);
            mean += p;
        }
        mean /= static_cast<double>(face.size());
        const double len = normal.norm();
        if (face.size() > 3 && len > 0) {
            const Vec3 u = normal / len;
            for (std::size_t k = 0; k < face.size(); ++k) {
                const double off = std::abs(u.dot(positions[face[k]] - r - mean));
                if (off > planeTol)
                    return fail(MassStatus::NonPlanarFace, static_cast<int>(f),
                                "face " + std::to_string(f) + ": vertex " + std::to_string(face[k]) + " is " +
                                    std::to_string(off) + " off the face plane (tolerance " + std::to_string(planeTol) +
                                    ")");
            }
        }
        // Fan (v0, vk, vk+1) with the reference point r.
        const Vec3 a = positions[face[0]] - r;
        for (std::size_t k = 1; k + 1 < face.size(); ++k) {
            const Vec3 b = positions[face[k]] - r, c = positions[face[k + 1]] - r;
            const double D = a.dot(b.cross(c));
            const Vec3 s = a + b + c;
            six += D;
            first += D * s;
            second += D * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
        }
    }
    const double volume = six / 6.0;
    // Degenerate: relative to the bounding box volume scale diagonal^3 (kMassDegenerateVolume).
    if (!(volume > kMassDegenerateVolume * diagonal * diagonal * diagonal))
        return fail(MassStatus::Degenerate, -1,
                    "volume " + volumeText(volume) + " is not above 1e-12 x its bounding box diagonal cubed (" +
                        volumeText(kMassDegenerateVolume * diagonal * diagonal * diagonal) +
                        "): flat, empty, inside-out (faces must be counter-clockwise from outside), or too thin for "
                        "its length to weigh in double precision");

    MassProperties m;
    m.status = MassStatus::Ok;
    m.volume = volume;
    m.mass = density * volume;
    const Vec3 d = first / 24.0 / volume;  // centre relative to r
    m.centerOfMass = r + d;
    const Mat3 covariance = second / 120.0 - volume * (d * d.transpose());
    Mat3 inertia = covariance.trace() * Mat3::Identity() - covariance;
    inertia = 0.5 * (inertia + inertia.transpose());  // symmetric to the last bit
    m.inertia = density * inertia;
    return m;
}

MassProperties computeMassProperties(const ConvexPolyhedron& polyhedron, const MassPropertiesOptions& options) {
    std::vector<std::vector<int>> faces;
    faces.reserve(polyhedron.faceCount());
    for (int f = 0; f < polyhedron.faceCount(); ++f) faces.push_back(polyhedron.faceVertices(f));
    return computeMassProperties(polyhedron.positions(), faces, options);
}

Mat3 inertiaAboutPoint(const Mat3& inertia, double mass, const Vec3& centerOfMass, const Vec3& point) {
    const Vec3 d = point - centerOfMass;
    return inertia + mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
}

}  // namespace cdlab
