#include "core/contact/contact_sat.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "core/base/tolerances.h"
#include "core/closest/closest_point.h"

namespace cdlab {

const char* nameOf(SatContactStatus status) {
    switch (status) {
        case SatContactStatus::Separated: return "Separated";
        case SatContactStatus::Touching: return "Touching";
        case SatContactStatus::Penetrating: return "Penetrating";
        case SatContactStatus::InvalidInput: return "InvalidInput";
    }
    return "InvalidInput";
}

const char* nameOf(SatAxisKind kind) {
    switch (kind) {
        case SatAxisKind::FaceA: return "face A";
        case SatAxisKind::FaceB: return "face B";
        case SatAxisKind::EdgeEdge: return "edge-edge";
    }
    return "face A";
}

namespace {

// A posed polyhedron in world orientation, positions relative to the common origin o.
struct Posed {
    const ConvexPolyhedron* mesh = nullptr;
    std::vector<Vec3> x;         // vertices
    std::vector<Vec3> n;         // face normals (unit)
    std::vector<double> d;       // face offsets: n · x = d
    Vec3 center = Vec3::Zero();  // vertex mean (inside: convex)

    Posed(const ConvexPolyhedron& m, const Transform& t, const Vec3& origin) : mesh(&m) {
        const Vec3 shift = t.position - origin;  // exact when t.position == origin
        for (const auto& v : m.vertices()) {
            x.push_back(t.rotation * v.position + shift);
            center += x.back();
        }
        center /= double(x.size());
        for (int f = 0; f < m.faceCount(); ++f) {
            n.push_back(t.rotation * m.face(f).normal);
            // Offset at the face's vertex mean (as the mesh does): rounding averages out.
            Vec3 c = Vec3::Zero();
            int k = 0;
            m.forEachFaceHalfEdge(f, [&](int h) {
                c += x[m.halfEdge(h).origin];
                ++k;
            });
            d.push_back(n.back().dot(c / double(k)));
        }
    }
    // min over vertices of dir · x (the support value in -dir, negated).
    double minProjection(const Vec3& dir) const {
        double m = INFINITY;
        for (const Vec3& p : x) m = std::min(m, dir.dot(p));
        return m;
    }
    std::vector<Vec3> facePolygon(int f) const {
        std::vector<Vec3> p;
        mesh->forEachFaceHalfEdge(f, [&](int h) { p.push_back(x[mesh->halfEdge(h).origin]); });
        return p;
    }
};

std::string checkPose(const Transform& pose) {
    if (!pose.position.allFinite() || !pose.rotation.coeffs().allFinite()) return "pose is not finite";
    // A typo-level error, not rounding drift (~1e-15 per multiplication).
    if (std::abs(pose.rotation.squaredNorm() - 1.0) > 1e-6) return "pose rotation is not a unit quaternion";
    return {};
}

// Gregorius' arc test (file comment): do the Gauss-map arcs a→b and c→d intersect?
bool isMinkowskiFace(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const Vec3 bxa = b.cross(a), dxc = d.cross(c);
    const double cba = c.dot(bxa), dba = d.dot(bxa), adc = a.dot(dxc), bdc = b.dot(dxc);
    return cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0;
}

// Sutherland–Hodgman against one plane (Ericson §8.3.4): keep n · x <= d.
std::vector<Vec3> clipPolygon(const std::vector<Vec3>& poly, const Vec3& n, double d) {
    std::vector<Vec3> out;
    const size_t k = poly.size();
    for (size_t i = 0; i < k; ++i) {
        const Vec3& p = poly[i];
        const Vec3& q = poly[(i + 1) % k];
        const double sp = n.dot(p) - d, sq = n.dot(q) - d;
        if (sp <= 0.0) out.push_back(p);
        if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) out.push_back(p + (sp / (sp - sq)) * (q - p));
    }
    return out;
}

// Every axis tested (for the trace), the best of each family and its index in axes.
struct SatQuery {
    std::vector<SatAxisRecord> axes;
    SatAxisRecord bestA{SatAxisKind::FaceA, -1, -1, Vec3::Zero(), -INFINITY};
    SatAxisRecord bestB{SatAxisKind::FaceB, -1, -1, Vec3::Zero(), -INFINITY};
    SatAxisRecord bestE{SatAxisKind::EdgeEdge, -1, -1, Vec3::Zero(), -INFINITY};
    int bestFaceAIndex = -1, bestFaceBIndex = -1, bestEdgeIndex = -1, pruned = 0, parallel = 0;
};

// 1. Face axes of A, then of B (B's normal points from B toward A: the axis A→B is -n).
void queryFaceAxes(const ConvexPolyhedron& ma, const Posed& A, const ConvexPolyhedron& mb, const Posed& B,
                   SatQuery& q) {
    auto& [axes, bestA, bestB, bestE, bestFaceAIndex, bestFaceBIndex, bestEdgeIndex, pruned, parallel] = q;
    for (int f = 0; f < ma.faceCount(); ++f) {
        const SatAxisRecord rec{SatAxisKind::FaceA, f, -1, A.n[f], B.minProjection(A.n[f]) - A.d[f]};
        if (rec.separation > bestA.separation) bestA = rec;
        axes.push_back(rec);
    }
    bestFaceAIndex = static_cast<int>(
        std::find_if(axes.begin(), axes.end(), [&](const SatAxisRecord& x) { return x.indexA == bestA.indexA; }) -
        axes.begin());
    for (int f = 0; f < mb.faceCount(); ++f) {
        const SatAxisRecord rec{SatAxisKind::FaceB, -1, f, -B.n[f], A.minProjection(B.n[f]) - B.d[f]};
        if (rec.separation > bestB.separation) bestB = rec, bestFaceBIndex = static_cast<int>(axes.size());
        axes.push_back(rec);
    }
}

// 2. Edge pairs that form a face of the Minkowski difference (their Gauss-map arcs cross), the
// axis their cross product, oriented away from A.
void queryEdgeAxes(const ConvexPolyhedron& ma, const Posed& A, const ConvexPolyhedron& mb, const Posed& B,
                   SatQuery& q) {
    auto& [axes, bestA, bestB, bestE, bestFaceAIndex, bestFaceBIndex, bestEdgeIndex, pruned, parallel] = q;
    for (int ea = 0; ea < ma.edgeCount(); ++ea) {
        const auto [a0, a1] = ma.edgeVertices(ea);
        const auto [fa1, fa2] = ma.edgeFaces(ea);
        const Vec3 da = A.x[a1] - A.x[a0];
        for (int eb = 0; eb < mb.edgeCount(); ++eb) {
            const auto [fb1, fb2] = mb.edgeFaces(eb);
            if (!isMinkowskiFace(A.n[fa1], A.n[fa2], -B.n[fb1], -B.n[fb2])) {
                ++pruned;
                continue;
            }
            const auto [b0, b1] = mb.edgeVertices(eb);
            const Vec3 db = B.x[b1] - B.x[b0];
            Vec3 axis = da.cross(db);
            // Parallel edges (sin of the angle below 1e-9: the cross product is rounding noise);
            // their separating direction is a face normal, tested in step 1.
            const double len = axis.norm();
            if (!(len > 1e-9 * da.norm() * db.norm())) {
                ++parallel;
                continue;
            }
            axis /= len;
            if (axis.dot(A.x[a0] - A.center) < 0.0) axis = -axis;  // away from A
            const SatAxisRecord rec{SatAxisKind::EdgeEdge, ea, eb, axis, axis.dot(B.x[b0] - A.x[a0])};
            if (rec.separation > bestE.separation) bestE = rec, bestEdgeIndex = static_cast<int>(axes.size());
            axes.push_back(rec);
        }
    }
}

struct ChosenAxis {
    SatAxisRecord best;
    int chosen = -1;      // its index in the query's axes
    double maxSep = 0.0;  // the largest separation over all axes
};

// 3. Separated: the axis of largest separation. Otherwise the axis of least penetration, with
// faces preferred to edges and A's faces to B's unless the other is better by the bias.
ChosenAxis chooseAxis(const SatQuery& q, double tol, const SatContactOptions& options) {
    const auto& [axes, bestA, bestB, bestE, bestFaceAIndex, bestFaceBIndex, bestEdgeIndex, pruned, parallel] = q;
    ChosenAxis c;
    const double maxSep = c.maxSep = std::max({bestA.separation, bestB.separation, bestE.separation});
    SatAxisRecord& best = c.best;
    int& chosen = c.chosen;
    best = bestA;
    chosen = bestFaceAIndex;
    if (maxSep > tol) {  // separated: the axis of largest separation, no preference needed
        if (bestB.separation == maxSep) best = bestB, chosen = bestFaceBIndex;
        if (bestE.separation == maxSep && best.separation != maxSep) best = bestE, chosen = bestEdgeIndex;
    } else {
        const double biasAbs = std::max(0.0, options.faceBiasAbsolute);
        const auto better = [&](const SatAxisRecord& c) {
            return c.separation >
                   best.separation + options.faceBiasRelative * std::abs(best.separation) + biasAbs + tol;
        };
        if (bestB.indexB >= 0 && better(bestB)) best = bestB, chosen = bestFaceBIndex;
        if (bestE.indexA >= 0 && better(bestE)) best = bestE, chosen = bestEdgeIndex;
    }
    return c;
}

// 4a. Edge–edge: one point, the closest points of the two edges.
void edgeContact(const ConvexPolyhedron& ma, const Posed& A, const ConvexPolyhedron& mb, const Posed& B,
                 const SatAxisRecord& best, const Vec3& origin, SatContactResult& r, SatContactTrace* trace) {
    const auto [a0, a1] = ma.edgeVertices(best.indexA);
    const auto [b0, b1] = mb.edgeVertices(best.indexB);
    const SegmentSegmentResult c = closestPointsSegmentSegment(Segment{A.x[a0], A.x[a1]}, Segment{B.x[b0], B.x[b1]});
    r.featureA = {FeatureType::Edge, best.indexA};
    r.featureB = {FeatureType::Edge, best.indexB};
    r.manifold.push_back({c.pointOnFirst + origin, c.pointOnSecond + origin, r.depth});
    if (trace) {
        trace->edgePointA = c.pointOnFirst + origin;
        trace->edgePointB = c.pointOnSecond + origin;
    }
}

// 4b. Face contact: reference face on A (FaceA) or B (FaceB); incident face = the other body's
// face most anti-parallel to the reference normal, clipped by the reference face's side planes
// (Sutherland–Hodgman), the points behind the reference plane kept and reduced.
void faceContact(const Posed& A, const Posed& B, const SatAxisRecord& best, const Vec3& origin, double tol,
                 const SatContactOptions& options, SatContactResult& r, SatContactTrace* trace) {
    const bool refOnA = best.kind == SatAxisKind::FaceA;
    const Posed& R = refOnA ? A : B;
    const Posed& I = refOnA ? B : A;
    const int rf = refOnA ? best.indexA : best.indexB;
    const Vec3 nr = R.n[rf];
    int inc = 0;
    for (int f = 1; f < I.mesh->faceCount(); ++f)
        if (I.n[f].dot(nr) < I.n[inc].dot(nr)) inc = f;
    const std::vector<Vec3> refPoly = R.facePolygon(rf);
    std::vector<Vec3> poly = I.facePolygon(inc);
    if (trace) {
        trace->referenceOnA = refOnA;
        trace->referenceFace = rf;
        trace->incidentFace = inc;
        for (const Vec3& p : refPoly) trace->referencePolygon.push_back(p + origin);
        for (const Vec3& p : poly) trace->incidentPolygon.push_back(p + origin);
    }
    // Side planes of the reference face: edge e_i = r_{i+1} - r_i (CCW about nr), outward
    // normal e_i x nr.
    for (size_t i = 0; i < refPoly.size() && !poly.empty(); ++i) {
        const Vec3 e = refPoly[(i + 1) % refPoly.size()] - refPoly[i];
        const Vec3 sn = e.cross(nr).normalized();
        const double sd = sn.dot(refPoly[i]);
        std::vector<Vec3> next = clipPolygon(poly, sn, sd);
        if (trace) {
            SatClipStep step{static_cast<int>(i), sn, sd + sn.dot(origin), {}, {}};
            for (const Vec3& p : poly) step.before.push_back(p + origin);
            for (const Vec3& p : next) step.after.push_back(p + origin);
            trace->clipSteps.push_back(step);
        }
        poly = std::move(next);
    }
    // Keep the points behind the reference plane: depth = -(nr · p - d).
    std::vector<ContactPoint> pts;
    for (const Vec3& p : poly) {
        const double s = nr.dot(p) - R.d[rf];
        if (s > tol) continue;
        const Vec3 onRef = p - s * nr;
        const double depth = std::max(0.0, -s);
        // A/B convention: the incident point belongs to the incident body.
        if (refOnA) pts.push_back({onRef + origin, p + origin, depth});
        else pts.push_back({p + origin, onRef + origin, depth});
    }
    if (pts.empty()) {
        // Clipping left nothing (the incident face only grazes the reference prism within
        // rounding): fall back to the incident body's deepest vertex along -nr.
        int v = 0;
        for (int i = 1; i < static_cast<int>(I.x.size()); ++i)
            if (nr.dot(I.x[i]) < nr.dot(I.x[v])) v = i;
        const double s = nr.dot(I.x[v]) - R.d[rf];
        const Vec3 onRef = I.x[v] - s * nr;
        if (refOnA) pts.push_back({onRef + origin, I.x[v] + origin, std::max(0.0, -s)});
        else pts.push_back({I.x[v] + origin, onRef + origin, std::max(0.0, -s)});
    }
    std::vector<ManifoldReductionStep> steps;
    for (int i : reduceContactPolygon(pts, nr, options.maxPoints, trace ? &steps : nullptr))
        r.manifold.push_back(pts[i]);
    r.featureA = {FeatureType::Face, refOnA ? rf : inc};
    r.featureB = {FeatureType::Face, refOnA ? inc : rf};
    if (trace) {
        trace->clipped = pts;
        trace->reduction = steps;
    }
}

}  // namespace

// Gregorius, "The Separating Axis Test between Convex Polyhedra" (GDC 2013) and "Robust Contact
// Creation for Physics Simulations" (GDC 2015): face axes, edge axes pruned on the Gauss map,
// the axis chosen with a face preference, then the contact from clipping.
SatContactResult contactPolyhedra(const ConvexPolyhedron& ma, const Transform& ta, const ConvexPolyhedron& mb,
                                  const Transform& tb, const SatContactOptions& options, SatContactTrace* trace) {
    SatContactResult r;
    if (ma.empty() || mb.empty()) r.message = "empty polyhedron";
    else if (std::string m = checkPose(ta); !m.empty()) r.message = "A: " + m;
    else if (std::string m2 = checkPose(tb); !m2.empty()) r.message = "B: " + m2;
    if (!r.message.empty()) {
        r.separation = r.depth = NAN;
        return r;
    }
    if (trace) *trace = SatContactTrace{};
    const Vec3 origin = ta.position;
    const Posed A(ma, ta, origin), B(mb, tb, origin);
    double maxCoord = 0.0;
    for (const Vec3& p : B.x) maxCoord = std::max(maxCoord, p.cwiseAbs().maxCoeff());
    maxCoord += origin.cwiseAbs().maxCoeff();
    const double size = std::max((ma.boundsMax() - ma.boundsMin()).norm(), (mb.boundsMax() - mb.boundsMin()).norm());
    // Touching band: relative to the size, plus 64 ulps of the coordinates (support values are
    // dot products of coordinates up to maxCoord, rounded to a few ulps).
    r.tolerance = options.tolerance >= 0.0 ? options.tolerance : 1e-9 * size + ulps(64, maxCoord);
    const double tol = r.tolerance;

    SatQuery q;
    queryFaceAxes(ma, A, mb, B, q);
    queryEdgeAxes(ma, A, mb, B, q);
    const ChosenAxis c = chooseAxis(q, tol, options);
    const SatAxisRecord& best = c.best;
    r.separation = c.maxSep;
    r.normal = best.axis;
    r.axisKind = best.kind;
    r.depth = std::max(0.0, -best.separation);
    r.status = c.maxSep > tol     ? SatContactStatus::Separated
               : c.maxSep >= -tol ? SatContactStatus::Touching
                                  : SatContactStatus::Penetrating;
    if (trace) {
        trace->axes = q.axes;
        trace->edgePairsTotal = ma.edgeCount() * mb.edgeCount();
        trace->edgePairsPruned = q.pruned;
        trace->edgePairsParallel = q.parallel;
        trace->bestFaceA = q.bestFaceAIndex;
        trace->bestFaceB = q.bestFaceBIndex;
        trace->bestEdgePair = q.bestEdgeIndex;
        trace->chosen = c.chosen;
    }
    if (r.status == SatContactStatus::Separated) {
        if (best.kind == SatAxisKind::EdgeEdge)
            r.featureA = {FeatureType::Edge, best.indexA}, r.featureB = {FeatureType::Edge, best.indexB};
        else if (best.kind == SatAxisKind::FaceA) r.featureA = {FeatureType::Face, best.indexA};
        else r.featureB = {FeatureType::Face, best.indexB};
        return r;
    }
    if (best.kind == SatAxisKind::EdgeEdge) edgeContact(ma, A, mb, B, best, origin, r, trace);
    else faceContact(A, B, best, origin, tol, options, r, trace);
    return r;
}

}  // namespace cdlab
