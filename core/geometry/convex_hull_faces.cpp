// The faces of the convex hull: the finished triangulation's triangles grouped into nearly
// coplanar groups, folds merged, each group's boundary loop as a polygon, collinear vertices
// removed (see core/geometry/convex_hull.h for the tolerances).
#include "core/geometry/convex_hull_internal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_set>
#include <utility>
#include <vector>

namespace cdlab::hull_internal {

AliveTriangles aliveTriangles(const std::vector<Tri>& tris) {
    AliveTriangles at{tris, std::vector<int>(tris.size(), -1), {}};
    for (int f = 0; f < static_cast<int>(tris.size()); ++f) {
        if (tris[f].alive) {
            at.compact[f] = static_cast<int>(at.alive.size());
            at.alive.push_back(f);
        }
    }
    return at;
}

FaceGroups groupCoplanar(const AliveTriangles& at, const std::vector<Vec3>& P, double mergeTol,
                         const HullOptions& options) {
    const auto& tris = at.tris;
    const auto& alive = at.alive;
    const auto& compact = at.compact;
    const int T = static_cast<int>(alive.size());
    // Group nearly coplanar neighbours around seed triangles, largest area first (its plane is the
    // most accurate). Every member's vertices are within mergeTol of the seed plane, so groups
    // cannot creep around a curved surface.
    std::vector<double> area2(T);
    for (int t = 0; t < T; ++t) {
        const Tri& tri = tris[alive[t]];
        area2[t] = (P[tri.v[1]] - P[tri.v[0]]).cross(P[tri.v[2]] - P[tri.v[0]]).norm();
    }
    std::vector<int> seeds(T);
    std::iota(seeds.begin(), seeds.end(), 0);
    std::stable_sort(seeds.begin(), seeds.end(), [&](int a, int b) { return area2[a] > area2[b]; });
    FaceGroups fg{std::vector<int>(T, -1), {}};
    std::vector<int>& group = fg.group;
    std::vector<std::vector<int>>& members = fg.members;
    for (int s : seeds) {
        if (group[s] >= 0) continue;
        const int gid = static_cast<int>(members.size());
        members.emplace_back(1, s);
        group[s] = gid;
        if (!options.mergeCoplanarFaces) continue;
        const Vec3 sn = tris[alive[s]].n;
        const double sd = tris[alive[s]].d;
        for (size_t qi = 0; qi < members[gid].size(); ++qi) {
            const Tri& tri = tris[alive[members[gid][qi]]];
            for (int k = 0; k < 3; ++k) {
                const int nb = compact[tri.adj[k]];
                if (group[nb] >= 0) continue;
                const Tri& other = tris[tri.adj[k]];
                bool coplanar = true;
                for (int j = 0; j < 3; ++j) coplanar = coplanar && std::abs(sn.dot(P[other.v[j]]) - sd) <= mergeTol;
                if (coplanar) {
                    group[nb] = gid;
                    members[gid].push_back(nb);
                }
            }
        }
    }

    return fg;
}

// Fold removal (as Qhull merges facets across non-convex ridges, Barber et al. §4): two groups
// meeting at an edge where a vertex of one lies more than eps in front of the other's plane
// are merged, until every edge is convex. This matters when points lie a few eps off a plane
// (noise just above eps): the construction is then only eps-accurate in position, and a thin
// triangle's plane, extended over the whole hull, can be far from supporting.
void mergeFolds(const AliveTriangles& at, const std::vector<Vec3>& P, double mergeTol, FaceGroups& fg) {
    const auto& tris = at.tris;
    const auto& alive = at.alive;
    const auto& compact = at.compact;
    const int T = static_cast<int>(alive.size());
    std::vector<int>& group = fg.group;
    std::vector<std::vector<int>>& members = fg.members;
    const int G = static_cast<int>(members.size());
    std::vector<int> uf(G);
    std::iota(uf.begin(), uf.end(), 0);
    auto find = [&](int x) {
        while (uf[x] != x) x = uf[x] = uf[uf[x]];
        return x;
    };
    std::vector<Vec3> areaVec(T), centroidOf(T);
    for (int t = 0; t < T; ++t) {
        const Tri& tri = tris[alive[t]];
        areaVec[t] = accurateCross(P[tri.v[0]], P[tri.v[1]], P[tri.v[2]]);
        centroidOf[t] = (P[tri.v[0]] + P[tri.v[1]] + P[tri.v[2]]) / 3.0;
    }
    // A group's fitted plane may sit up to mergeTol off its members' vertices, so a fold must
    // be deeper than that (2 * mergeTol) to be told apart from fitting error.
    const double foldTol = 2.0 * mergeTol;
    std::vector<Vec3> sumArea(G), sumMoment(G), normal(G);
    std::vector<double> sumWeight(G), offset(G);
    for (int round = 0; round < 64; ++round) {  // 64: folds are rare and shallow; a bound, not a tuning
        std::fill(sumArea.begin(), sumArea.end(), Vec3::Zero());
        std::fill(sumMoment.begin(), sumMoment.end(), Vec3::Zero());
        std::fill(sumWeight.begin(), sumWeight.end(), 0.0);
        for (int t = 0; t < T; ++t) {
            const int g = find(group[t]);
            const double w = areaVec[t].norm();
            sumArea[g] += areaVec[t];
            sumMoment[g] += w * centroidOf[t];
            sumWeight[g] += w;
        }
        for (int g = 0; g < G; ++g) {
            if (find(g) != g) continue;
            const double len = sumArea[g].norm();
            normal[g] = len > 0.0 ? Vec3(sumArea[g] / len) : Vec3::UnitZ();
            offset[g] = sumWeight[g] > 0.0 ? normal[g].dot(sumMoment[g] / sumWeight[g]) : 0.0;
        }
        bool changed = false;
        for (int t = 0; t < T; ++t) {
            const Tri& tri = tris[alive[t]];
            for (int k = 0; k < 3; ++k) {
                const int u = compact[tri.adj[k]];
                if (u < t) continue;  // each edge once
                const int A = find(group[t]), B = find(group[u]);
                if (A == B) continue;
                const Tri& other = tris[tri.adj[k]];
                int cu = other.v[0];
                for (int j = 0; j < 3; ++j) {
                    if (other.v[j] != tri.v[k] && other.v[j] != tri.v[(k + 1) % 3]) cu = other.v[j];
                }
                const int ct = tri.v[(k + 2) % 3];
                if (normal[A].dot(P[cu]) - offset[A] > foldTol || normal[B].dot(P[ct]) - offset[B] > foldTol) {
                    uf[std::max(A, B)] = std::min(A, B);
                    changed = true;
                }
            }
        }
        if (!changed) break;
    }
    std::vector<std::vector<int>> merged(G);
    for (int t = 0; t < T; ++t) {
        group[t] = find(group[t]);
        merged[group[t]].push_back(t);
    }
    members.clear();
    for (int g = 0; g < G; ++g) {
        if (merged[g].empty()) continue;
        for (int t : merged[g]) group[t] = static_cast<int>(members.size());
        members.push_back(std::move(merged[g]));
    }
}

FacePolygons facePolygons(const AliveTriangles& at, const std::vector<Vec3>& P, double mergeTol, const FaceGroups& fg) {
    const auto& tris = at.tris;
    const auto& alive = at.alive;
    const auto& compact = at.compact;
    const std::vector<int>& group = fg.group;
    const std::vector<std::vector<int>>& members = fg.members;
    const int n = static_cast<int>(P.size());
    FacePolygons out;
    std::vector<std::vector<int>>& loops = out.loops;
    int& mergedGroups = out.mergedGroups;
    int& rejected = out.rejected;
    std::vector<int> nextOf(n, -1);
    for (int gid = 0; gid < static_cast<int>(members.size()); ++gid) {
        const auto& mem = members[gid];
        auto emitTriangles = [&]() {
            for (int t : mem) {
                const Tri& tri = tris[alive[t]];
                loops.push_back({tri.v[0], tri.v[1], tri.v[2]});
            }
        };
        if (mem.size() == 1) {
            emitTriangles();
            continue;
        }
        std::vector<int> origins;
        bool ok = true;
        for (int t : mem) {
            const Tri& tri = tris[alive[t]];
            for (int k = 0; k < 3; ++k) {
                if (group[compact[tri.adj[k]]] == gid) continue;
                const int a = tri.v[k], b = tri.v[(k + 1) % 3];
                if (nextOf[a] >= 0) ok = false;  // pinched: the region touches itself at a
                nextOf[a] = b;
                origins.push_back(a);
            }
        }
        std::vector<int> loop;
        if (ok && !origins.empty()) {
            int v = origins[0];
            do {
                loop.push_back(v);
                v = nextOf[v];
            } while (v >= 0 && v != origins[0] && loop.size() <= origins.size());
            ok = v == origins[0] && loop.size() == origins.size();
        }
        for (int a : origins) nextOf[a] = -1;
        if (ok) {
            // Convex within tolerance: each corner b must not lie inside the chord a -> c by more
            // than mergeTol (a reflex corner would be a fold of the surface).
            const Vec3& sn = tris[alive[mem[0]]].n;
            const size_t k = loop.size();
            for (size_t i = 0; ok && i < k; ++i) {
                const Vec3& a = P[loop[(i + k - 1) % k]];
                const Vec3& b = P[loop[i]];
                const Vec3& c = P[loop[(i + 1) % k]];
                const Vec3 chord = c - a;
                const double len = chord.norm();
                if (!(len > 0.0)) {
                    ok = false;
                    break;
                }
                const Vec3 inward = sn.cross(chord) / len;
                if (inward.dot(b - a) > mergeTol) ok = false;
            }
        }
        if (ok) {
            ++mergedGroups;
            loops.push_back(std::move(loop));
        } else {
            ++rejected;
            emitTriangles();
        }
    }
    return out;
}

// Removes boundary vertices that have exactly two incident faces and lie within tol of the
// segment joining their neighbours. Such a vertex has the same two neighbours in both faces (in
// opposite order), so removing it from both keeps the mesh consistent. Returns the count removed.
int removeCollinear(std::vector<std::vector<int>>& loops, const std::vector<Vec3>& P, double tol) {
    std::vector<int> entryVertex, entryNext, entryPrev, entryFace;
    std::vector<int> faceHead(loops.size()), faceSize(loops.size());
    std::vector<std::vector<int>> entriesOf;
    int maxVertex = -1;
    for (const auto& l : loops)
        for (int v : l) maxVertex = std::max(maxVertex, v);
    entriesOf.resize(maxVertex + 1);
    for (int f = 0; f < static_cast<int>(loops.size()); ++f) {
        const int base = static_cast<int>(entryVertex.size());
        const int k = static_cast<int>(loops[f].size());
        for (int i = 0; i < k; ++i) {
            entryVertex.push_back(loops[f][i]);
            entryNext.push_back(base + (i + 1) % k);
            entryPrev.push_back(base + (i + k - 1) % k);
            entryFace.push_back(f);
            entriesOf[loops[f][i]].push_back(base + i);
        }
        faceHead[f] = base;
        faceSize[f] = k;
    }
    auto edgeKey = [](int a, int b) {
        if (a > b) std::swap(a, b);
        return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
    };
    std::unordered_set<std::uint64_t> edges;
    for (const auto& l : loops)
        for (size_t i = 0; i < l.size(); ++i) edges.insert(edgeKey(l[i], l[(i + 1) % l.size()]));
    int removed = 0;
    bool changed = true;
    while (changed) {
        changed = false;
        for (int v = 0; v <= maxVertex; ++v) {
            if (entriesOf[v].size() != 2) continue;
            const int e1 = entriesOf[v][0], e2 = entriesOf[v][1];
            const int f1 = entryFace[e1], f2 = entryFace[e2];
            if (f1 == f2 || faceSize[f1] <= 3 || faceSize[f2] <= 3) continue;
            const int u = entryVertex[entryPrev[e1]], w = entryVertex[entryNext[e1]];
            if (entryVertex[entryNext[e2]] != u || entryVertex[entryPrev[e2]] != w) continue;
            if (edges.count(edgeKey(u, w))) continue;  // u-w already an edge: removal would pinch the mesh
            const Vec3 uw = P[w] - P[u];
            const double len2 = uw.squaredNorm();
            if (!(len2 > 0.0)) continue;
            const double t = (P[v] - P[u]).dot(uw) / len2;
            if (!(t > 0.0 && t < 1.0)) continue;
            if ((P[v] - P[u] - t * uw).norm() > tol) continue;
            for (int e : {e1, e2}) {
                entryNext[entryPrev[e]] = entryNext[e];
                entryPrev[entryNext[e]] = entryPrev[e];
                const int f = entryFace[e];
                if (faceHead[f] == e) faceHead[f] = entryNext[e];
                --faceSize[f];
            }
            entriesOf[v].clear();
            edges.erase(edgeKey(u, v));
            edges.erase(edgeKey(v, w));
            edges.insert(edgeKey(u, w));
            ++removed;
            changed = true;
        }
    }
    for (int f = 0; f < static_cast<int>(loops.size()); ++f) {
        loops[f].clear();
        int e = faceHead[f];
        for (int i = 0; i < faceSize[f]; ++i, e = entryNext[e]) loops[f].push_back(entryVertex[e]);
    }
    return removed;
}

}  // namespace cdlab::hull_internal
