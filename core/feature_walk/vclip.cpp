// V-Clip (Mirtich 1998, MERL TR-97-05): Voronoi regions of a half-edge polyhedron and the walk.
#include "core/feature_walk/vclip.h"

#include <cmath>

namespace cdlab {

const char* nameOf(VClipFeatureType type) {
    switch (type) {
        case VClipFeatureType::Vertex: return "vertex";
        case VClipFeatureType::Edge: return "edge";
        case VClipFeatureType::Face: return "face";
        case VClipFeatureType::None: break;
    }
    return "none";
}

std::string nameOf(const VClipFeature& f) {
    switch (f.type) {
        case VClipFeatureType::Vertex: return "V" + std::to_string(f.index);
        case VClipFeatureType::Edge: return "E" + std::to_string(f.index);
        case VClipFeatureType::Face: return "F" + std::to_string(f.index);
        case VClipFeatureType::None: break;
    }
    return "-";
}

const char* nameOf(VClipBuildStatus status) {
    switch (status) {
        case VClipBuildStatus::Ok: return "Ok";
        case VClipBuildStatus::EmptyPolyhedron: return "EmptyPolyhedron";
        case VClipBuildStatus::InvalidMesh: return "InvalidMesh";
        case VClipBuildStatus::CoplanarFaces: return "CoplanarFaces";
    }
    return "?";
}

const char* nameOf(VClipStatus status) {
    switch (status) {
        case VClipStatus::Separated: return "Separated";
        case VClipStatus::Penetrating: return "Penetrating";
        case VClipStatus::CycleDetected: return "CycleDetected";
        case VClipStatus::StepLimit: return "StepLimit";
        case VClipStatus::InvalidInput: return "InvalidInput";
    }
    return "?";
}

const char* nameOf(VClipPenetration how) {
    switch (how) {
        case VClipPenetration::None: return "None";
        case VClipPenetration::EdgePiercesFace: return "EdgePiercesFace";
        case VClipPenetration::LocalMinimum: return "LocalMinimum";
        case VClipPenetration::Touching: return "Touching";
    }
    return "?";
}

const char* nameOf(VClipState state) {
    switch (state) {
        case VClipState::VertexVertex: return "V-V";
        case VClipState::VertexEdge: return "V-E";
        case VClipState::VertexFace: return "V-F";
        case VClipState::EdgeEdge: return "E-E";
        case VClipState::EdgeFace: return "E-F";
    }
    return "?";
}

const char* nameOf(VClipStepKind kind) {
    switch (kind) {
        case VClipStepKind::Update: return "Update";
        case VClipStepKind::Done: return "Done";
        case VClipStepKind::Penetration: return "Penetration";
        case VClipStepKind::Aborted: return "Aborted";
    }
    return "?";
}

// ---------------------------------------------------------------------------------------------
// Voronoi planes (Mirtich §3.1): for edge e = tail -> head with unit direction u,
//   VE tail:  normal  u, through tail   (positive side: towards the edge)
//   VE head:  normal -u, through head
//   FE left:  normal u x nL, through tail (nL: left face normal; n x u points into the face,
//             so u x n points away from it, towards the edge side)
//   FE right: normal -u x nR = nR x u (the twin half-edge runs head -> tail)
VClipBuild buildVClipPolyhedron(const ConvexPolyhedron& poly) {
    VClipBuild out;
    if (poly.empty()) {
        out.status = VClipBuildStatus::EmptyPolyhedron;
        out.message = "vclip: empty polyhedron";
        return out;
    }
    const PolyhedronCheck check = poly.validate();
    if (!check.ok()) {
        out.status = VClipBuildStatus::InvalidMesh;
        out.message = std::string("vclip: invalid polyhedron (") + nameOf(check.defect) + "): " + check.message;
        return out;
    }
    VClipPolyhedron& p = out.polyhedron;
    const int ne = poly.edgeCount(), nv = poly.vertexCount(), nf = poly.faceCount();
    p.edgeTail_.resize(ne);
    p.edgeHead_.resize(ne);
    p.edgeLeft_.resize(ne);
    p.edgeRight_.resize(ne);
    p.planes_.resize(4 * static_cast<size_t>(ne));
    for (int e = 0; e < ne; ++e) {
        const int h = poly.edge(e).halfEdge;
        const int t = poly.halfEdge(h).origin, hd = poly.halfEdgeDestination(h);
        const int fl = poly.halfEdge(h).face, fr = poly.halfEdge(poly.halfEdge(h).twin).face;
        p.edgeTail_[e] = t;
        p.edgeHead_[e] = hd;
        p.edgeLeft_[e] = fl;
        p.edgeRight_[e] = fr;
        const Vec3& a = poly.position(t);
        const Vec3& b = poly.position(hd);
        const Vec3 u = (b - a).normalized();
        const Vec3& nl = poly.face(fl).normal;
        const Vec3& nr = poly.face(fr).normal;
        // Adjacent coplanar faces make VR(e) a flat wedge and the walk ambiguous. 1e-12 (in
        // sin of the dihedral deviation) is ~4500 ulps: below it the two face normals are equal
        // up to the rounding of their own computation (Newell normals of a merged hull face
        // agree to ~1e-15); any modelled crease is far above it.
        if (nl.cross(nr).norm() <= 1e-12 && nl.dot(nr) > 0.0) {
            out.status = VClipBuildStatus::CoplanarFaces;
            out.message = "vclip: faces " + std::to_string(fl) + " and " + std::to_string(fr) + " sharing edge " +
                          std::to_string(e) + " are coplanar; merge them (convexHull merges coplanar faces)";
            out.polyhedron = VClipPolyhedron{};
            return out;
        }
        const Vec3 fln = u.cross(nl).normalized();
        const Vec3 frn = nr.cross(u).normalized();
        const VClipFeature fe = VClipFeature::edge(e);
        p.planes_[4 * e + 0] = VClipPlane{u, u.dot(a), fe, VClipFeature::vertex(t)};
        p.planes_[4 * e + 1] = VClipPlane{-u, -u.dot(b), fe, VClipFeature::vertex(hd)};
        p.planes_[4 * e + 2] = VClipPlane{fln, fln.dot(a), fe, VClipFeature::face(fl)};
        p.planes_[4 * e + 3] = VClipPlane{frn, frn.dot(a), fe, VClipFeature::face(fr)};
    }
    // CSR region lists: vertex v gets the VE plane of each incident edge at v, face f the FE
    // plane of each boundary edge on f's side, both in the mesh's counter-clockwise orders.
    p.vertexStart_.assign(nv + 1, 0);
    p.faceStart_.assign(nf + 1, 0);
    p.regionPlanes_.clear();
    p.regionPlanes_.reserve(4 * static_cast<size_t>(ne));
    for (int v = 0; v < nv; ++v) {
        p.vertexStart_[v] = static_cast<int>(p.regionPlanes_.size());
        poly.forEachVertexHalfEdge(v, [&](int h) {
            const int e = poly.halfEdge(h).edge;
            p.regionPlanes_.push_back(4 * e + (p.edgeTail_[e] == v ? 0 : 1));
        });
    }
    p.vertexStart_[nv] = static_cast<int>(p.regionPlanes_.size());
    const int base = static_cast<int>(p.regionPlanes_.size());
    for (int f = 0; f < nf; ++f) {
        p.faceStart_[f] = static_cast<int>(p.regionPlanes_.size()) - base;
        poly.forEachFaceHalfEdge(f, [&](int h) {
            const int e = poly.halfEdge(h).edge;
            p.regionPlanes_.push_back(4 * e + (p.edgeLeft_[e] == f ? 2 : 3));
        });
    }
    p.faceStart_[nf] = static_cast<int>(p.regionPlanes_.size()) - base;
    for (int& s : p.faceStart_) s += base;
    p.mesh_ = poly;
    out.status = VClipBuildStatus::Ok;
    return out;
}

std::vector<Vec3> featureGeometry(const VClipPolyhedron& p, const Transform& pose, const VClipFeature& f) {
    std::vector<Vec3> pts;
    const ConvexPolyhedron& m = p.mesh();
    switch (f.type) {
        case VClipFeatureType::Vertex: pts.push_back(pose.apply(m.position(f.index))); break;
        case VClipFeatureType::Edge:
            pts.push_back(pose.apply(m.position(p.edgeTail(f.index))));
            pts.push_back(pose.apply(m.position(p.edgeHead(f.index))));
            break;
        case VClipFeatureType::Face:
            for (int v : m.faceVertices(f.index)) pts.push_back(pose.apply(m.position(v)));
            break;
        case VClipFeatureType::None: break;
    }
    return pts;
}

}  // namespace cdlab
