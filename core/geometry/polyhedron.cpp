#include "core/geometry/polyhedron.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <unordered_map>

#include "core/base/tolerances.h"

namespace cdlab {

namespace {

std::uint64_t directedKey(int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

std::string fmt(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

PolyhedronCheck fail(PolyhedronDefect defect, int index, std::string message) {
    return PolyhedronCheck{defect, index, std::move(message)};
}

// Newell's method (Newell 1972; Ericson §12.4.1): the normal of a possibly non-planar polygon as
// its area vector, here the sum of the fan's accurate cross products (the same vector).
void fitPlane(const std::vector<Vec3>& positions, const std::vector<int>& loop, Vec3& normal, double& offset) {
    Vec3 mean = Vec3::Zero();
    for (int v : loop) mean += positions[v];
    mean /= static_cast<double>(loop.size());
    Vec3 n = Vec3::Zero();
    const Vec3& a = positions[loop[0]];
    for (size_t i = 1; i + 1 < loop.size(); ++i) n += accurateCross(a, positions[loop[i]], positions[loop[i + 1]]);
    const double len = n.norm();
    // A zero-area face gets an arbitrary unit normal; validate() then reports it as non-planar
    // or as a vertex outside, rather than propagating NaN.
    normal = len > 0.0 ? Vec3(n / len) : Vec3::UnitZ();
    offset = normal.dot(mean);
}

}  // namespace

const char* nameOf(PolyhedronDefect defect) {
    switch (defect) {
        case PolyhedronDefect::None: return "None";
        case PolyhedronDefect::NoFaces: return "NoFaces";
        case PolyhedronDefect::BadVertexIndex: return "BadVertexIndex";
        case PolyhedronDefect::FaceTooSmall: return "FaceTooSmall";
        case PolyhedronDefect::RepeatedVertexInFace: return "RepeatedVertexInFace";
        case PolyhedronDefect::NonManifoldEdge: return "NonManifoldEdge";
        case PolyhedronDefect::OpenEdge: return "OpenEdge";
        case PolyhedronDefect::IsolatedVertex: return "IsolatedVertex";
        case PolyhedronDefect::NonManifoldVertex: return "NonManifoldVertex";
        case PolyhedronDefect::BrokenLinks: return "BrokenLinks";
        case PolyhedronDefect::NonFinite: return "NonFinite";
        case PolyhedronDefect::EulerMismatch: return "EulerMismatch";
        case PolyhedronDefect::NonUnitNormal: return "NonUnitNormal";
        case PolyhedronDefect::NonPlanarFace: return "NonPlanarFace";
        case PolyhedronDefect::NonConvexFace: return "NonConvexFace";
        case PolyhedronDefect::VertexOutside: return "VertexOutside";
        case PolyhedronDefect::NonPositiveVolume: return "NonPositiveVolume";
    }
    return "Unknown";
}

PolyhedronBuild ConvexPolyhedron::translated(const Vec3& offset) const {
    std::vector<Vec3> moved = positions();
    for (Vec3& p : moved) p += offset;
    std::vector<std::vector<int>> faces;
    faces.reserve(faces_.size());
    for (int f = 0; f < faceCount(); ++f) faces.push_back(faceVertices(f));
    return fromFaces(std::move(moved), faces);
}

PolyhedronBuild ConvexPolyhedron::fromFaces(std::vector<Vec3> positions, const std::vector<std::vector<int>>& faces) {
    PolyhedronBuild out;
    const int vertexCount = static_cast<int>(positions.size());
    for (int v = 0; v < vertexCount; ++v) {
        if (!positions[v].allFinite()) {
            out.check =
                fail(PolyhedronDefect::NonFinite, v, "vertex " + std::to_string(v) + " has a non-finite coordinate");
            return out;
        }
    }
    if (faces.size() < 4 || vertexCount < 4) {
        out.check = fail(PolyhedronDefect::NoFaces, -1, "a closed polyhedron needs at least 4 faces and 4 vertices");
        return out;
    }
    ConvexPolyhedron poly;
    std::unordered_map<std::uint64_t, int> directed;
    size_t totalHalfEdges = 0;
    for (const auto& f : faces) totalHalfEdges += f.size();
    directed.reserve(totalHalfEdges * 2);
    poly.halfEdges_.reserve(totalHalfEdges);
    poly.faces_.reserve(faces.size());

    for (int fi = 0; fi < static_cast<int>(faces.size()); ++fi) {
        const auto& loop = faces[fi];
        const int k = static_cast<int>(loop.size());
        if (k < 3) {
            out.check =
                fail(PolyhedronDefect::FaceTooSmall, fi, "face " + std::to_string(fi) + " has fewer than 3 vertices");
            return out;
        }
        for (int i = 0; i < k; ++i) {
            if (loop[i] < 0 || loop[i] >= vertexCount) {
                out.check = fail(
                    PolyhedronDefect::BadVertexIndex, fi,
                    "face " + std::to_string(fi) + " refers to vertex " + std::to_string(loop[i]) + " out of range");
                return out;
            }
            for (int j = 0; j < i; ++j) {
                if (loop[j] == loop[i]) {
                    out.check =
                        fail(PolyhedronDefect::RepeatedVertexInFace, fi,
                             "face " + std::to_string(fi) + " visits vertex " + std::to_string(loop[i]) + " twice");
                    return out;
                }
            }
        }
        const int base = static_cast<int>(poly.halfEdges_.size());
        for (int i = 0; i < k; ++i) {
            HalfEdge h;
            h.origin = loop[i];
            h.next = base + (i + 1) % k;
            h.prev = base + (i + k - 1) % k;
            h.face = fi;
            const int a = loop[i], b = loop[(i + 1) % k];
            if (!directed.emplace(directedKey(a, b), base + i).second) {
                out.check = fail(PolyhedronDefect::NonManifoldEdge, fi,
                                 "directed edge " + std::to_string(a) + "->" + std::to_string(b) +
                                     " used by two faces (second: face " + std::to_string(fi) + ")");
                return out;
            }
            poly.halfEdges_.push_back(h);
        }
        Face face;
        face.halfEdge = base;
        fitPlane(positions, loop, face.normal, face.offset);
        poly.faces_.push_back(face);
    }
    for (int h = 0; h < static_cast<int>(poly.halfEdges_.size()); ++h) {
        HalfEdge& he = poly.halfEdges_[h];
        const int b = poly.halfEdges_[he.next].origin;
        const auto it = directed.find(directedKey(b, he.origin));
        if (it == directed.end()) {
            out.check = fail(PolyhedronDefect::OpenEdge, h,
                             "half-edge " + std::to_string(h) + " (" + std::to_string(he.origin) + "->" +
                                 std::to_string(b) + ") has no twin: surface not closed");
            return out;
        }
        he.twin = it->second;
        if (he.twin < h) {
            he.edge = poly.halfEdges_[he.twin].edge;
        } else {
            he.edge = static_cast<int>(poly.edges_.size());
            poly.edges_.push_back(Edge{h});
        }
    }
    poly.vertices_.resize(vertexCount);
    std::vector<int> outDegree(vertexCount, 0);
    for (int v = 0; v < vertexCount; ++v) poly.vertices_[v].position = positions[v];
    for (int h = 0; h < static_cast<int>(poly.halfEdges_.size()); ++h) {
        const int v = poly.halfEdges_[h].origin;
        if (poly.vertices_[v].halfEdge < 0) poly.vertices_[v].halfEdge = h;
        ++outDegree[v];
    }
    for (int v = 0; v < vertexCount; ++v) {
        if (poly.vertices_[v].halfEdge < 0) {
            out.check =
                fail(PolyhedronDefect::IsolatedVertex, v, "vertex " + std::to_string(v) + " belongs to no face");
            return out;
        }
        int count = 0;
        poly.forEachVertexHalfEdge(v, [&](int) { ++count; });
        if (count != outDegree[v]) {
            out.check = fail(PolyhedronDefect::NonManifoldVertex, v,
                             "the faces around vertex " + std::to_string(v) + " form more than one fan");
            return out;
        }
    }
    if (poly.eulerCharacteristic() != 2) {
        out.check = fail(PolyhedronDefect::EulerMismatch, -1,
                         "V - E + F = " + std::to_string(poly.eulerCharacteristic()) + ", not 2");
        return out;
    }
    assert(poly.checkLinks().ok());
    poly.flattenTopology();
    out.polyhedron = std::move(poly);
    return out;
}

void ConvexPolyhedron::flattenTopology() {
    edgeEnds_.clear();
    edgeEnds_.reserve(edges_.size());
    for (int e = 0; e < edgeCount(); ++e) {
        const auto [v0, v1] = edgeVertices(e);
        const auto [f1, f2] = edgeFaces(e);
        edgeEnds_.push_back({v0, v1, f1, f2});
    }
    neighborStart_.assign(vertices_.size() + 1, 0);
    for (const HalfEdge& h : halfEdges_) ++neighborStart_[h.origin + 1];
    for (size_t v = 0; v < vertices_.size(); ++v) neighborStart_[v + 1] += neighborStart_[v];
    neighbors_.assign(halfEdges_.size(), Neighbor{});
    std::vector<int> fill(neighborStart_.begin(), neighborStart_.end() - 1);
    for (const HalfEdge& h : halfEdges_) {
        const int w = halfEdges_[h.twin].origin;
        neighbors_[fill[h.origin]++] = {w, h.edge, position(w) - position(h.origin)};
    }
    faceVertexStart_.assign(1, 0);
    faceVertexIds_.clear();
    faceVertexIds_.reserve(halfEdges_.size());
    faceAcross_.clear();
    faceAcross_.reserve(halfEdges_.size());
    for (int f = 0; f < faceCount(); ++f) {
        forEachFaceHalfEdge(f, [&](int h) {
            faceVertexIds_.push_back(halfEdges_[h].origin);
            faceAcross_.push_back(halfEdges_[halfEdges_[h].twin].face);
        });
        faceVertexStart_.push_back(static_cast<int>(faceVertexIds_.size()));
    }
}

std::vector<Vec3> ConvexPolyhedron::positions() const {
    std::vector<Vec3> out;
    out.reserve(vertices_.size());
    for (const auto& v : vertices_) out.push_back(v.position);
    return out;
}

std::pair<int, int> ConvexPolyhedron::edgeVertices(int e) const {
    const int h = edges_[e].halfEdge;
    return {halfEdges_[h].origin, halfEdgeDestination(h)};
}

std::pair<int, int> ConvexPolyhedron::edgeFaces(int e) const {
    const int h = edges_[e].halfEdge;
    return {halfEdges_[h].face, halfEdges_[halfEdges_[h].twin].face};
}

int ConvexPolyhedron::faceDegree(int f) const {
    int count = 0;
    forEachFaceHalfEdge(f, [&](int) { ++count; });
    return count;
}

std::vector<int> ConvexPolyhedron::faceVertices(int f) const {
    std::vector<int> out;
    forEachFaceHalfEdge(f, [&](int h) { out.push_back(halfEdges_[h].origin); });
    return out;
}

std::vector<int> ConvexPolyhedron::vertexHalfEdges(int v) const {
    return aroundVertex(v, [&](int h) { return h; });
}

std::vector<int> ConvexPolyhedron::vertexFaces(int v) const {
    return aroundVertex(v, [&](int h) { return halfEdges_[h].face; });
}

std::vector<int> ConvexPolyhedron::vertexNeighbors(int v) const {
    return aroundVertex(v, [&](int h) { return halfEdgeDestination(h); });
}

std::vector<int> ConvexPolyhedron::vertexEdges(int v) const {
    return aroundVertex(v, [&](int h) { return halfEdges_[h].edge; });
}

Vec3 ConvexPolyhedron::vertexMean() const {
    Vec3 o = Vec3::Zero();
    for (const auto& v : vertices_) o += v.position;
    return o / static_cast<double>(vertices_.size());
}

template <class Fn>
void ConvexPolyhedron::forEachFanTetrahedron(const Vec3& o, Fn&& fn) const {
    for (int f = 0; f < faceCount(); ++f) {
        const int h0 = faces_[f].halfEdge;
        const Vec3 a = position(halfEdges_[h0].origin) - o;
        for (int h = halfEdges_[h0].next; halfEdges_[h].next != h0; h = halfEdges_[h].next)
            fn(a, Vec3(position(halfEdges_[h].origin) - o), Vec3(position(halfEdgeDestination(h)) - o));
    }
}

double ConvexPolyhedron::volume() const {
    if (vertices_.empty()) return 0.0;
    double sum = 0.0;
    forEachFanTetrahedron(vertexMean(), [&](const Vec3& a, const Vec3& b, const Vec3& c) {
        sum += a.dot(b.cross(c));  // 6 x signed volume of tetrahedron (o, a, b, c)
    });
    return sum / 6.0;
}

Vec3 ConvexPolyhedron::centroid() const {
    if (vertices_.empty()) return Vec3::Zero();
    const Vec3 o = vertexMean();
    double total = 0.0;
    Vec3 moment = Vec3::Zero();
    forEachFanTetrahedron(o, [&](const Vec3& a, const Vec3& b, const Vec3& c) {
        const double v6 = a.dot(b.cross(c));
        total += v6;
        moment += v6 * (a + b + c) / 4.0;  // tetrahedron (0, a, b, c) centroid
    });
    if (!(total > 0.0)) return o;
    return o + moment / total;
}

double ConvexPolyhedron::surfaceArea() const {
    double area = 0.0;
    for (int f = 0; f < faceCount(); ++f) {
        const int h0 = faces_[f].halfEdge;
        const Vec3& a = position(halfEdges_[h0].origin);
        Vec3 sum = Vec3::Zero();
        for (int h = halfEdges_[h0].next; halfEdges_[h].next != h0; h = halfEdges_[h].next) {
            sum += (position(halfEdges_[h].origin) - a).cross(position(halfEdgeDestination(h)) - a);
        }
        area += 0.5 * sum.norm();
    }
    return area;
}

Vec3 ConvexPolyhedron::boundsMin() const {
    if (vertices_.empty()) return Vec3::Zero();
    Vec3 m = vertices_[0].position;
    for (const auto& v : vertices_) m = m.cwiseMin(v.position);
    return m;
}

Vec3 ConvexPolyhedron::boundsMax() const {
    if (vertices_.empty()) return Vec3::Zero();
    Vec3 m = vertices_[0].position;
    for (const auto& v : vertices_) m = m.cwiseMax(v.position);
    return m;
}

double ConvexPolyhedron::scaleTolerance() const { return scaleTolerance(boundsMin(), boundsMax()); }

double ConvexPolyhedron::scaleTolerance(const Vec3& lo, const Vec3& hi) {
    const double maxAbs = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    return ulps(65536.0, maxAbs + (hi - lo).norm());
}

PolyhedronCheck ConvexPolyhedron::validate(std::optional<double> requested) const {
    const double tolerance = requested && !(*requested < 0.0) ? *requested : scaleTolerance();
    const int V = vertexCount(), F = faceCount();
    if (V < 4 || F < 4) return fail(PolyhedronDefect::NoFaces, -1, "fewer than 4 vertices or faces");
    // 1-3. Links, face cycles, vertex fans.
    if (PolyhedronCheck links = checkLinks(); !links.ok()) return links;
    // 4. Topology of a sphere.
    if (eulerCharacteristic() != 2) {
        return fail(PolyhedronDefect::EulerMismatch, -1,
                    "V - E + F = " + std::to_string(eulerCharacteristic()) + ", not 2");
    }
    // 5. Geometry: finite values, unit normals, planar and convex faces.
    for (int v = 0; v < V; ++v) {
        if (!vertices_[v].position.allFinite()) {
            return fail(PolyhedronDefect::NonFinite, v, "vertex " + std::to_string(v) + " is not finite");
        }
    }
    for (int f = 0; f < F; ++f) {
        if (PolyhedronCheck face = checkFaceGeometry(f, tolerance); !face.ok()) return face;
    }
    // 6. Convexity of the solid: every vertex on or behind every face plane.
    if (PolyhedronCheck solid = checkSolidConvexity(tolerance); !solid.ok()) return solid;
    if (!(volume() > 0.0)) return fail(PolyhedronDefect::NonPositiveVolume, -1, "volume is not positive");
    return PolyhedronCheck{};
}

PolyhedronCheck ConvexPolyhedron::checkLinks() const {
    const int V = vertexCount(), H = halfEdgeCount(), F = faceCount(), E = edgeCount();
    auto inRange = [](int i, int n) { return i >= 0 && i < n; };
    // 1. Pointer consistency of every half-edge.
    for (int h = 0; h < H; ++h) {
        const HalfEdge& he = halfEdges_[h];
        const bool ok =
            inRange(he.origin, V) && inRange(he.twin, H) && inRange(he.next, H) && inRange(he.prev, H) &&
            inRange(he.face, F) && inRange(he.edge, E) && he.twin != h && halfEdges_[he.twin].twin == h &&
            halfEdges_[he.next].prev == h && halfEdges_[he.prev].next == h && halfEdges_[he.next].face == he.face &&
            halfEdges_[he.twin].origin == halfEdges_[he.next].origin && halfEdges_[he.twin].edge == he.edge &&
            (edges_[he.edge].halfEdge == h || edges_[he.edge].halfEdge == he.twin);
        if (!ok) {
            return fail(PolyhedronDefect::BrokenLinks, h,
                        "half-edge " + std::to_string(h) + " has inconsistent twin/next/prev/face/edge");
        }
    }
    // 2. Face cycles: each closes, has >= 3 half-edges, and together they cover every half-edge once.
    std::vector<int> seen(H, -1);
    int covered = 0;
    for (int f = 0; f < F; ++f) {
        const int start = faces_[f].halfEdge;
        if (!inRange(start, H) || halfEdges_[start].face != f) {
            return fail(PolyhedronDefect::BrokenLinks, f, "face " + std::to_string(f) + " has a bad half-edge");
        }
        int h = start, count = 0;
        do {
            if (seen[h] >= 0) {
                return fail(PolyhedronDefect::BrokenLinks, f,
                            "face " + std::to_string(f) + " cycle revisits a half-edge");
            }
            seen[h] = f;
            ++count;
            h = halfEdges_[h].next;
        } while (h != start);
        if (count < 3) {
            return fail(PolyhedronDefect::FaceTooSmall, f, "face " + std::to_string(f) + " has fewer than 3 vertices");
        }
        covered += count;
    }
    if (covered != H) return fail(PolyhedronDefect::BrokenLinks, -1, "some half-edges belong to no face cycle");
    // 3. Vertex fans: the ring twin(prev(h)) visits every outgoing half-edge of the vertex exactly once.
    std::vector<int> outDegree(V, 0);
    for (int h = 0; h < H; ++h) ++outDegree[halfEdges_[h].origin];
    for (int v = 0; v < V; ++v) {
        const int start = vertices_[v].halfEdge;
        if (!inRange(start, H) || halfEdges_[start].origin != v) {
            return fail(PolyhedronDefect::IsolatedVertex, v,
                        "vertex " + std::to_string(v) + " has no valid outgoing half-edge");
        }
        int h = start, count = 0;
        do {
            ++count;
            h = halfEdges_[halfEdges_[h].prev].twin;
        } while (h != start && count <= H);
        if (count != outDegree[v]) {
            return fail(PolyhedronDefect::NonManifoldVertex, v,
                        "the faces around vertex " + std::to_string(v) + " form more than one fan");
        }
    }
    return PolyhedronCheck{};
}

// Finite unit normal, every vertex within tolerance of the plane, convex within tolerance.
PolyhedronCheck ConvexPolyhedron::checkFaceGeometry(int f, double tolerance) const {
    const Face& face = faces_[f];
    if (!face.normal.allFinite() || !std::isfinite(face.offset)) {
        return fail(PolyhedronDefect::NonFinite, f, "face " + std::to_string(f) + " plane is not finite");
    }
    if (std::abs(face.normal.norm() - 1.0) > kUnitNormalTolerance) {
        return fail(PolyhedronDefect::NonUnitNormal, f, "face " + std::to_string(f) + " normal is not unit");
    }
    const std::vector<int> loop = faceVertices(f);
    const size_t k = loop.size();
    for (int v : loop) {
        const double dist = std::abs(planeDistance(f, position(v)));
        if (dist > tolerance) {
            return fail(
                PolyhedronDefect::NonPlanarFace, f,
                "vertex " + std::to_string(v) + " is " + fmt(dist) + " off the plane of face " + std::to_string(f));
        }
    }
    // Every vertex of the face on the inner side of every edge line of the face (in the
    // face plane): catches reflex corners and self-overlapping (star) cycles.
    for (size_t i = 0; i < k; ++i) {
        const Vec3& a = position(loop[i]);
        const Vec3 ab = position(loop[(i + 1) % k]) - a;
        const double len = ab.norm();
        if (!(len > 0.0)) {
            return fail(PolyhedronDefect::NonConvexFace, f, "face " + std::to_string(f) + " has a zero-length edge");
        }
        const Vec3 inward = face.normal.cross(ab) / len;  // in-plane, pointing into the face
        for (size_t j = 0; j < k; ++j) {
            if (j == i || j == (i + 1) % k) continue;
            if (inward.dot(position(loop[j]) - a) < -tolerance) {
                return fail(PolyhedronDefect::NonConvexFace, f,
                            "vertex " + std::to_string(loop[j]) + " lies outside edge " + std::to_string(loop[i]) +
                                "->" + std::to_string(loop[(i + 1) % k]) + " of face " + std::to_string(f));
            }
        }
    }
    return PolyhedronCheck{};
}

// Every vertex on or behind every face plane (all pairs when V*F <= 2e7, else the neighbours of
// each face's vertices, which for a closed genus-0 surface implies global convexity).
PolyhedronCheck ConvexPolyhedron::checkSolidConvexity(double tolerance) const {
    const int V = vertexCount(), F = faceCount();
    auto outsideMessage = [&](int v, int f, double d) {
        return "vertex " + std::to_string(v) + " is " + fmt(d) + " in front of face " + std::to_string(f);
    };
    if (static_cast<double>(V) * static_cast<double>(F) <= 2e7) {
        for (int f = 0; f < F; ++f) {
            for (int v = 0; v < V; ++v) {
                const double d = planeDistance(f, position(v));
                if (d > tolerance) return fail(PolyhedronDefect::VertexOutside, v, outsideMessage(v, f, d));
            }
        }
    } else {
        // Local convexity: for every face, the neighbours of its vertices are behind its plane.
        for (int f = 0; f < F; ++f) {
            int bad = -1;
            double badDist = 0.0;
            forEachFaceHalfEdge(f, [&](int h) {
                forEachVertexHalfEdge(halfEdges_[h].origin, [&](int g) {
                    const int w = halfEdgeDestination(g);
                    const double d = planeDistance(f, position(w));
                    if (d > tolerance && bad < 0) {
                        bad = w;
                        badDist = d;
                    }
                });
            });
            if (bad >= 0) return fail(PolyhedronDefect::VertexOutside, bad, outsideMessage(bad, f, badDist));
        }
    }
    return PolyhedronCheck{};
}

}  // namespace cdlab
