#include "core/geometry/shapes.h"

#include "core/geometry/polyhedron.h"

namespace cdlab {

namespace {

void computeExtremes(const std::vector<Vec3>& v, std::array<int, 6>& ext, double& radius) {
    ext.fill(0);
    radius = 0.0;
    for (int i = 0; i < static_cast<int>(v.size()); ++i) {
        for (int k = 0; k < 3; ++k) {
            if (v[i][k] > v[ext[2 * k]][k]) ext[2 * k] = i;
            if (v[i][k] < v[ext[2 * k + 1]][k]) ext[2 * k + 1] = i;
        }
        radius = std::max(radius, v[i].norm());
    }
}

}  // namespace

PolytopeShape::PolytopeShape(std::vector<Vec3> vertices) : vertices_(std::move(vertices)) {
    computeExtremes(vertices_, axisExtremes_, boundingRadius_);
}

PolytopeShape::PolytopeShape(const ConvexPolyhedron& polyhedron) : vertices_(polyhedron.positions()) {
    computeExtremes(vertices_, axisExtremes_, boundingRadius_);
    if (vertices_.empty()) return;
    adjacencyStart_.reserve(vertices_.size() + 1);
    adjacencyStart_.push_back(0);
    for (int v = 0; v < polyhedron.vertexCount(); ++v) {
        polyhedron.forEachVertexHalfEdge(v, [&](int h) { adjacency_.push_back(polyhedron.halfEdgeDestination(h)); });
        adjacencyStart_.push_back(static_cast<int>(adjacency_.size()));
    }
}

std::span<const int> PolytopeShape::neighbors(int i) const {
    if (!hasAdjacency()) return {};
    return std::span<const int>(adjacency_.data() + adjacencyStart_[i],
                                static_cast<size_t>(adjacencyStart_[i + 1] - adjacencyStart_[i]));
}

int PolytopeShape::supportIndexLoop(const Vec3& d) const {
    // Plain scalar loop: measured as fast as SSE2 structure-of-arrays variants (two-lane blend,
    // max-then-scan) for 8..64 vertices on x86-64, whose compare / select chain is the bottleneck.
    const int n = vertexCount();
    if (n == 0) return -1;
    const Vec3* p = vertices_.data();
    int best = 0;
    double bestValue = d.dot(p[0]);
    for (int i = 1; i < n; ++i) {
        const double value = d.dot(p[i]);
        if (value > bestValue) {  // strict: the first maximal vertex wins ties; NaN never wins
            bestValue = value;
            best = i;
        }
    }
    return best;
}

int PolytopeShape::seedVertex(const Vec3& d) const {
    int best = axisExtremes_[0];
    double bestValue = d.dot(vertices_[best]);
    for (int k = 1; k < 6; ++k) {
        const double value = d.dot(vertices_[axisExtremes_[k]]);
        if (value > bestValue) {
            bestValue = value;
            best = axisExtremes_[k];
        }
    }
    return best;
}

int PolytopeShape::supportIndexClimb(const Vec3& d, int start) const {
    if (!hasAdjacency()) return supportIndexLoop(d);
    // Zero or NaN direction: every vertex is maximal (or none is); answer like the loop.
    if (!(d.squaredNorm() > 0.0)) return vertexCount() > 0 ? 0 : -1;
    if (start < 0 || start >= vertexCount()) start = seedVertex(d);
    int v = start;
    double fv = d.dot(vertices_[v]);
    // Plateau of vertices with value exactly fv, explored breadth-first (fixed capacity: no
    // allocation; a larger plateau falls back to the loop, which is exact and deterministic).
    constexpr int kPlateauCapacity = 64;
    std::array<int, kPlateauCapacity> plateau;
    for (;;) {
        // Steepest ascent: best strictly higher neighbour (lower index on ties).
        int next = -1;
        double fnext = fv;
        bool level = false;  // some neighbour has exactly fv: v may sit on a plateau
        const int* nb = adjacency_.data() + adjacencyStart_[v];
        const int* nbEnd = adjacency_.data() + adjacencyStart_[v + 1];
        for (; nb != nbEnd; ++nb) {
            const int w = *nb;
            const double fw = d.dot(vertices_[w]);
            level = level || fw == fv;
            if (fw > fnext || (fw == fnext && next >= 0 && w < next)) {
                fnext = fw;
                next = w;
            }
        }
        if (next >= 0) {
            v = next;
            fv = fnext;
            continue;
        }
        if (!level) return v;  // strict local maximum: the global one, and alone on its plateau
        // No uphill neighbour: explore the plateau {value == fv} for an uphill exit.
        int count = 0;
        plateau[count++] = v;
        int exitVertex = -1;
        double fexit = fv;
        for (int head = 0; head < count && exitVertex < 0; ++head) {
            for (int w : neighbors(plateau[head])) {
                const double fw = d.dot(vertices_[w]);
                if (fw > fexit) {
                    fexit = fw;
                    exitVertex = w;
                } else if (fw == fv) {
                    bool seen = false;
                    for (int k = 0; k < count && !seen; ++k) seen = plateau[k] == w;
                    if (seen) continue;
                    if (count == kPlateauCapacity) return supportIndexLoop(d);
                    plateau[count++] = w;
                }
            }
        }
        if (exitVertex >= 0) {  // values strictly increase between plateaus: this terminates
            v = exitVertex;
            fv = fexit;
            continue;
        }
        int lowest = plateau[0];
        for (int k = 1; k < count; ++k) lowest = std::min(lowest, plateau[k]);
        return lowest;
    }
}

}  // namespace cdlab
