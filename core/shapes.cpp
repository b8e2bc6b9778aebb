#include "core/shapes.h"

#include "core/polyhedron.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

void fillSoa(const std::vector<Vec3>& v, std::vector<double>& soa) {
    const size_t n = v.size();
    soa.resize(3 * n);
    for (size_t i = 0; i < n; ++i) {
        soa[i] = v[i].x();
        soa[n + i] = v[i].y();
        soa[2 * n + i] = v[i].z();
    }
}

}  // namespace

PolytopeShape::PolytopeShape(std::vector<Vec3> vertices) : vertices_(std::move(vertices)) {
    computeExtremes(vertices_, axisExtremes_, boundingRadius_);
    fillSoa(vertices_, soa_);
}

PolytopeShape::PolytopeShape(const ConvexPolyhedron& polyhedron) : vertices_(polyhedron.positions()) {
    computeExtremes(vertices_, axisExtremes_, boundingRadius_);
    fillSoa(vertices_, soa_);
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
    const int n = vertexCount();
    if (n == 0) return -1;
    const double* xs = soa_.data();
    const double* ys = xs + n;
    const double* zs = ys + n;
    // value_i = (d.x x_i + d.y y_i) + d.z z_i, the same operations in the same order as
    // d.dot(vertex(i)) without FMA, so ties and the hill climbing's values agree bit for bit.
    int best = 0;
    double bestValue = (d.x() * xs[0] + d.y() * ys[0]) + d.z() * zs[0];
    int i = 1;
#if defined(__SSE2__)
    // Blocks of up to 64 vertices: pass 1 stores the values and takes a two-lane maximum
    // (maxpd returns its second operand, the running maximum, when the new value is NaN, so NaN
    // never wins; both lanes start at vertex 0's value as the scalar loop does); pass 2 returns
    // the first vertex whose value equals that maximum, i.e. the scalar loop's answer exactly.
    // A NaN maximum (vertex 0's value NaN) equals nothing: vertex 0, as the scalar loop.
    if (n >= 4) {
        const __m128d dx = _mm_set1_pd(d.x()), dy = _mm_set1_pd(d.y()), dz = _mm_set1_pd(d.z());
        constexpr int kBlock = 64;
        alignas(16) double values[kBlock];
        __m128d bestV = _mm_set1_pd(bestValue);
        int k = 0;
        while (k + 2 <= n) {
            const int blockBegin = k;
            const int blockEnd = std::min(n & ~1, k + kBlock);
            for (; k < blockEnd; k += 2) {
                const __m128d v = _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, _mm_loadu_pd(xs + k)),
                                                        _mm_mul_pd(dy, _mm_loadu_pd(ys + k))),
                                             _mm_mul_pd(dz, _mm_loadu_pd(zs + k)));
                _mm_store_pd(values + (k - blockBegin), v);
                bestV = _mm_max_pd(v, bestV);
            }
            double lanes[2];
            _mm_storeu_pd(lanes, bestV);
            const double blockMax = lanes[0] > lanes[1] || lanes[1] != lanes[1] ? lanes[0] : lanes[1];
            if (blockMax > bestValue) {  // this block holds the first vertex with the new maximum
                for (int m = blockBegin; m < blockEnd; ++m) {
                    if (values[m - blockBegin] == blockMax) {
                        best = m;
                        break;
                    }
                }
                bestValue = blockMax;
            }
            bestV = _mm_set1_pd(bestValue);
        }
        i = k;  // odd n: the last vertex is left for the scalar loop (a higher index: strict >)
    }
#endif
    for (; i < n; ++i) {
        const double value = (d.x() * xs[i] + d.y() * ys[i]) + d.z() * zs[i];
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
