// Convex polyhedron stored as a half-edge mesh (doubly connected edge list).
//
// Layout (de Berg et al., "Computational Geometry", 3rd ed., §2.2 DCEL; Mäntylä, "An Introduction
// to Solid Modeling", ch. 10): every undirected edge is a pair of twin half-edges with opposite
// directions; every face is the cycle of half-edges `next` walks, counter-clockwise seen from
// outside (so the right-hand rule over the cycle gives the outward normal). Indices are int,
// -1 means "none". The mesh is immutable after construction: build it with fromFaces() (or with
// convexHull() in core/geometry/convex_hull.h, or a preset in core/geometry/polyhedron_presets.h).
//
// Orders the iteration helpers guarantee (all "seen from outside", i.e. looking against the
// outward normal / towards the body):
//   faceVertices(f)      counter-clockwise around f.
//   vertexHalfEdges(v)   outgoing half-edges of v counter-clockwise around v; the next one after h
//                        is twin(prev(h)).
//   vertexFaces(v)       face(h) for h in vertexHalfEdges(v): face i lies between outgoing half-edge
//                        i and outgoing half-edge i+1 (counter-clockwise).
//   vertexNeighbors(v)   destination of each half-edge of vertexHalfEdges(v), same order.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/base/accurate_cross.h"  // accurateCross: face normals here, and for this header's includers
#include "core/base/types.h"

namespace cdlab {

/// validate(): a face normal is unit when | |n| - 1 | is at most this. A normal fitted and
/// normalized in double is unit to ~1e-16; anything farther was not normalized at all.
inline constexpr double kUnitNormalTolerance = 1e-9;

/// What validate() / fromFaces() found wrong first (None = nothing).
enum class PolyhedronDefect {
    None,
    NoFaces,               ///< fewer than 4 faces / empty mesh
    BadVertexIndex,        ///< a face refers to a vertex index out of range
    FaceTooSmall,          ///< a face with fewer than 3 vertices
    RepeatedVertexInFace,  ///< a face visits the same vertex twice
    NonManifoldEdge,       ///< a directed edge used by two faces (inconsistent orientation or > 2 faces)
    OpenEdge,              ///< a half-edge without twin: the surface is not closed
    IsolatedVertex,        ///< a vertex used by no face
    NonManifoldVertex,     ///< the faces around a vertex form more than one fan
    BrokenLinks,           ///< twin/next/prev/face/edge pointers inconsistent
    NonFinite,             ///< NaN/Inf position, normal or offset
    EulerMismatch,         ///< V - E + F != 2
    NonUnitNormal,         ///< face normal not of unit length
    NonPlanarFace,         ///< a face vertex farther than the tolerance from its face plane
    NonConvexFace,         ///< a face vertex outside an edge line of its own face
    VertexOutside,         ///< a vertex in front of a face plane by more than the tolerance
    NonPositiveVolume,     ///< inside-out or flat
};

/// Name of a defect, e.g. "NonPlanarFace".
const char* nameOf(PolyhedronDefect defect);

/// Result of a structural or geometric check: the first defect found, the element it concerns
/// (vertex, half-edge or face index, as the message says) and a one-line message.
struct PolyhedronCheck {
    PolyhedronDefect defect = PolyhedronDefect::None;
    int index = -1;
    std::string message;
    bool ok() const { return defect == PolyhedronDefect::None; }
};

struct PolyhedronBuild;

class ConvexPolyhedron {
public:
    struct Vertex {
        Vec3 position = Vec3::Zero();
        int halfEdge = -1;  ///< one outgoing half-edge
    };
    struct HalfEdge {
        int origin = -1;  ///< vertex the half-edge starts at
        int twin = -1;    ///< opposite half-edge (same edge, other face)
        int next = -1;    ///< next half-edge of the same face (counter-clockwise from outside)
        int prev = -1;    ///< previous half-edge of the same face
        int face = -1;    ///< face on the left of the half-edge (seen from outside)
        int edge = -1;    ///< undirected edge index
    };
    struct Face {
        int halfEdge = -1;            ///< one half-edge of the face cycle
        Vec3 normal = Vec3::UnitZ();  ///< unit outward normal (Newell area vector, body frame)
        double offset = 0.0;          ///< plane: normal · x = offset
    };
    struct Edge {
        int halfEdge = -1;  ///< the lower-indexed half-edge of the twin pair
    };

    /// Empty polyhedron (no vertices); use fromFaces() or a preset.
    ConvexPolyhedron() = default;

    /// Builds the half-edge mesh from positions and faces given as vertex-index cycles,
    /// counter-clockwise seen from outside. Checks topology only (indices, manifold, closed,
    /// no isolated vertex, Euler); face normals are Newell area vectors (sum of accurateCross over
    /// the face's fan) normalized, offsets taken at the vertex mean. Call validate() for convexity. On failure the
    /// returned polyhedron is empty.
    static PolyhedronBuild fromFaces(std::vector<Vec3> positions, const std::vector<std::vector<int>>& faces);
    /// The same faces with every vertex moved by `offset` (rebuilt by fromFaces: normals and offsets
    /// recomputed at the new place), e.g. a body recentred at its centre of mass.
    PolyhedronBuild translated(const Vec3& offset) const;

    int vertexCount() const { return static_cast<int>(vertices_.size()); }
    int halfEdgeCount() const { return static_cast<int>(halfEdges_.size()); }
    int edgeCount() const { return static_cast<int>(edges_.size()); }
    int faceCount() const { return static_cast<int>(faces_.size()); }
    bool empty() const { return vertices_.empty(); }

    const std::vector<Vertex>& vertices() const { return vertices_; }
    const std::vector<HalfEdge>& halfEdges() const { return halfEdges_; }
    const std::vector<Face>& faces() const { return faces_; }
    const std::vector<Edge>& edges() const { return edges_; }
    const Vertex& vertex(int v) const { return vertices_[v]; }
    const HalfEdge& halfEdge(int h) const { return halfEdges_[h]; }
    const Face& face(int f) const { return faces_[f]; }
    const Edge& edge(int e) const { return edges_[e]; }
    const Vec3& position(int v) const { return vertices_[v].position; }
    /// All vertex positions, index-aligned with vertices().
    std::vector<Vec3> positions() const;

    /// Destination vertex of half-edge h (= origin of next(h) = origin of twin(h)).
    int halfEdgeDestination(int h) const { return halfEdges_[halfEdges_[h].next].origin; }
    /// The two vertices of edge e: origin and destination of edge(e).halfEdge.
    std::pair<int, int> edgeVertices(int e) const;
    /// The two faces of edge e: face of edge(e).halfEdge, then face of its twin.
    std::pair<int, int> edgeFaces(int e) const;
    /// Number of vertices (= half-edges) of face f.
    int faceDegree(int f) const;
    /// Vertex indices of face f, counter-clockwise seen from outside, starting at origin of face(f).halfEdge.
    std::vector<int> faceVertices(int f) const;
    /// Outgoing half-edges of vertex v, counter-clockwise seen from outside.
    std::vector<int> vertexHalfEdges(int v) const;
    /// Faces around vertex v, counter-clockwise seen from outside (face of each outgoing half-edge).
    std::vector<int> vertexFaces(int v) const;
    /// Adjacent vertices of v (destinations of vertexHalfEdges(v)), same order.
    std::vector<int> vertexNeighbors(int v) const;
    /// Edges incident to v, in the order of vertexHalfEdges(v).
    std::vector<int> vertexEdges(int v) const;

    /// Pose-independent topology flattened at construction for the hot loops of the contact query
    /// (core/contact/contact_sat.h), which would otherwise walk the half-edge links on every call:
    /// one load per edge or neighbour instead of three dependent ones. Memory: ~48 bytes a half-edge
    /// on top of the links' 24, the neighbours' steps 24 of them (computing the steps per call
    /// instead measured 6% more instructions in contactPolyhedra).
    struct EdgeEnds {
        int v0 = -1, v1 = -1;  ///< edgeVertices(e)
        int f1 = -1, f2 = -1;  ///< edgeFaces(e)
    };
    struct Neighbor {
        int vertex = -1;            ///< destination of an outgoing half-edge
        int edge = -1;              ///< its undirected edge
        Vec3 step = Vec3::Zero();   ///< position(vertex) - position(origin), body frame
    };
    /// edgeEnds()[e]: edgeVertices(e) and edgeFaces(e).
    const std::vector<EdgeEnds>& edgeEnds() const { return edgeEnds_; }
    /// The neighbours of v are neighbors()[neighborStart()[v] .. neighborStart()[v + 1]), its
    /// outgoing half-edges in index order (not around the vertex: vertexNeighbors() gives that order).
    const std::vector<int>& neighborStart() const { return neighborStart_; }
    const std::vector<Neighbor>& neighbors() const { return neighbors_; }
    /// The vertices of face f are faceVertexIds()[faceVertexStart()[f] .. faceVertexStart()[f + 1]),
    /// faceVertices(f)'s order.
    const std::vector<int>& faceVertexStart() const { return faceVertexStart_; }
    const std::vector<int>& faceVertexIds() const { return faceVertexIds_; }
    /// Aligned with faceVertexIds(): the face across the edge from that vertex to the next one of f.
    const std::vector<int>& faceAcross() const { return faceAcross_; }

    /// Calls fn(halfEdgeIndex) for each half-edge of face f in cycle order; no allocation.
    template <class Fn>
    void forEachFaceHalfEdge(int f, Fn&& fn) const {
        const int start = faces_[f].halfEdge;
        int h = start;
        do {
            fn(h);
            h = halfEdges_[h].next;
        } while (h != start);
    }
    /// Calls fn(outgoingHalfEdge) for each outgoing half-edge of v, counter-clockwise; no allocation.
    template <class Fn>
    void forEachVertexHalfEdge(int v, Fn&& fn) const {
        const int start = vertices_[v].halfEdge;
        int h = start;
        do {
            fn(h);
            h = halfEdges_[halfEdges_[h].prev].twin;
        } while (h != start);
    }

    /// Signed distance of x from the plane of face f (positive in front, i.e. outside).
    double planeDistance(int f, const Vec3& x) const { return faces_[f].normal.dot(x) - faces_[f].offset; }
    /// The plane of face f (unit normal).
    Plane plane(int f) const { return Plane{faces_[f].normal, faces_[f].offset}; }

    /// V - E + F (2 for every valid convex polyhedron).
    int eulerCharacteristic() const { return vertexCount() - edgeCount() + faceCount(); }
    /// Enclosed volume (divergence theorem over face fans, relative to the vertex mean for accuracy
    /// at large offsets). Units: length^3. Positive for outward-oriented faces.
    double volume() const;
    /// Centroid (centre of mass of the uniform solid), body frame. Vertex mean if volume is 0.
    Vec3 centroid() const;
    /// Total face area. Units: length^2.
    double surfaceArea() const;
    /// Componentwise minimum / maximum of the vertex positions.
    Vec3 boundsMin() const;
    Vec3 boundsMax() const;
    /// Default geometric tolerance for this mesh: 65536 * DBL_EPSILON * (max |coordinate| + bounds
    /// diagonal), ~1.5e-11 of the scale. Well above what convexHull() leaves (faces planar within
    /// ~2 x its merge tolerance of 16384 * DBL_EPSILON * scale) and far below any modelled feature.
    double scaleTolerance() const;
    /// The same from bounds already at hand (boundsMin(), boundsMax()): no pass over the vertices.
    static double scaleTolerance(const Vec3& boundsMin, const Vec3& boundsMax);

    /// Full check: links (twin/next/prev/face/edge), closed 2-manifold with single vertex fans,
    /// Euler V - E + F = 2, finite unit normals, every face planar and convex within tolerance,
    /// every vertex on or behind every face plane (done for all pairs when V*F <= 2e7, otherwise
    /// for the neighbours of each face's vertices, which for a closed genus-0 surface implies
    /// global convexity), positive volume. std::nullopt (or a negative value) means scaleTolerance().
    PolyhedronCheck validate(std::optional<double> tolerance = std::nullopt) const;
    /// validate()'s structural part alone: every half-edge's twin / next / prev / face / edge
    /// consistent, face cycles closed and covering every half-edge once, one fan per vertex.
    /// fromFaces() asserts it on what it builds (on in the sanitizer build).
    PolyhedronCheck checkLinks() const;

private:
    /// map(h) for each outgoing half-edge h of v, counter-clockwise.
    template <class Map>
    std::vector<int> aroundVertex(int v, Map&& map) const {
        std::vector<int> out;
        forEachVertexHalfEdge(v, [&](int h) { out.push_back(map(h)); });
        return out;
    }

    /// Mean of the vertex positions (not empty).
    Vec3 vertexMean() const;
    /// fn(a, b, c) for each tetrahedron (o, a, b, c) of the faces' fans, coordinates relative to o
    /// (the vertex mean, for accuracy at large offsets).
    template <class Fn>
    void forEachFanTetrahedron(const Vec3& o, Fn&& fn) const;
    PolyhedronCheck checkFaceGeometry(int f, double tolerance) const;
    PolyhedronCheck checkSolidConvexity(double tolerance) const;
    /// Fills edgeEnds_, neighborStart_, neighbors_ and the face vertex lists from the half-edge links.
    void flattenTopology();
    std::vector<Vertex> vertices_;
    std::vector<HalfEdge> halfEdges_;
    std::vector<Face> faces_;
    std::vector<Edge> edges_;
    std::vector<EdgeEnds> edgeEnds_;
    std::vector<int> neighborStart_;
    std::vector<Neighbor> neighbors_;
    std::vector<int> faceVertexStart_, faceVertexIds_, faceAcross_;
};

/// Output of ConvexPolyhedron::fromFaces: the mesh (empty unless check.ok()) and the check.
struct PolyhedronBuild {
    ConvexPolyhedron polyhedron;
    PolyhedronCheck check;
    bool ok() const { return check.ok(); }
};

}  // namespace cdlab
