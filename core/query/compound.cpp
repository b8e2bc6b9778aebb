// Compound and mesh pair queries (core/query/compound.h): box culls, then core's pair query on the
// pairs of pieces that remain. Every search visits pairs in (a, b) order and keeps the first of
// equal answers, so an answer does not depend on which pairs the culls skipped. Tests:
// tests/app/query/query_compound_test.cpp and tests/app/query/hostile_query_test.cpp.
#include "core/query/compound.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/geometry/solid_mesh.h"
#include "core/spatial/convex_decomposition.h"

namespace cdlab {

namespace {

using Kind = QueryShape::Kind;

// Box gaps at or below this times the pair's largest finite box coordinate may still be touching
// pairs: far above the rounding of the gap and of the touching rule (1e-13 of the pair's extent,
// core/base/touch_rule.h).
constexpr double kCullMarginRelative = 1e-9;

// A unit mesh (size ~1) whose |signed volume| is at or below this times size^3 encloses no volume:
// rounding of the sum is ~1e-16 per triangle; a solid is far above 1e-12.
constexpr double kMinUnitVolume = 1e-12;

// Candidate planes a BSP node scores: scoring every triangle at every node is quadratic; 32 evenly
// spaced candidates (Ericson §8.3.2) give as many pieces on a torus (4273 vs 4210 of 10 000
// triangles) in a tenth of the time (0.3 s).
constexpr int kMeshPieceCandidates = 32;

}  // namespace

// ---------------------------------------------------------------------------------------------
// Bodies.

CompoundBody CompoundBody::shape(QueryShape s) {
    CompoundBody body;
    body.boundary = {std::move(s)};
    body.pieces = body.boundary;
    return body;
}

CompoundBody CompoundBody::compound(std::vector<QueryShape> shapes) {
    CompoundBody body;
    body.kind = Kind::Compound;
    body.boundary = std::move(shapes);
    body.pieces = body.boundary;
    return body;
}

std::optional<CompoundBody> CompoundBody::solidMesh(TriangleMesh mesh) {
    Vec3 lo = mesh.vertices[0], hi = lo;
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    // The volume of the mesh scaled by a power of two to a size of ~1 (exact): 1e-300 or 1e300
    // meshes neither underflow nor overflow the cubes.
    int e = 0;
    std::frexp(std::max((hi - lo).maxCoeff(), (0.5 * (hi + lo)).cwiseAbs().maxCoeff()), &e);
    CompoundBody body;
    body.kind = Kind::Mesh;
    body.unitExponent = -e;
    body.unitMesh = mesh;
    for (Vec3& v : body.unitMesh.vertices) v = scaled(v, -e);
    const double size = std::ldexp((hi - lo).maxCoeff(), -e);
    const double volume = signedVolume(body.unitMesh);
    if (!(std::abs(volume) > kMinUnitVolume * size * size * size)) return std::nullopt;
    if (volume < 0) {
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
        body.unitMesh.triangles = mesh.triangles;
    }
    body.mesh = std::move(mesh);
    for (int t = 0; t < body.mesh->triangleCount(); ++t) {
        const Triangle tri = body.mesh->triangle(t);
        body.boundary.push_back(QueryShape::triangle(tri.a, tri.b, tri.c));
    }
    return body;
}

std::vector<QueryShape> meshConvexPieces(const CompoundBody& body) {
    BspOptions options;
    options.maxCandidates = kMeshPieceCandidates;
    // On the mesh scaled to size ~1 (exact), so that 1e-300 or 1e300 meshes neither underflow nor
    // overflow the cells' volumes; the corners are scaled back.
    const ConvexDecomposition d = decomposeIntoConvexPieces(body.unitMesh, options);
    std::vector<QueryShape> pieces;
    for (const std::vector<Vec3>& corners : d.pieces) {
        QueryShape s;
        s.kind = Kind::Polytope;
        for (const Vec3& c : corners) s.vertices.push_back(scaled(c, -body.unitExponent));
        pieces.push_back(std::move(s));
    }
    return pieces;
}

namespace {

// ---------------------------------------------------------------------------------------------
// Pairs of pieces, culled by their bounding boxes.

struct PieceBox {
    Vec3 lo, hi;
};

PieceBox pieceBox(const QueryShape& s) {
    if (!s.bounded()) return {Vec3::Constant(-INFINITY), Vec3::Constant(INFINITY)};
    if (s.isCurved()) {
        PieceBox b;
        s.curved.bounds(b.lo, b.hi);
        return b;
    }
    PieceBox b{s.vertices[0], s.vertices[0]};
    for (const Vec3& v : s.vertices) b.lo = b.lo.cwiseMin(v), b.hi = b.hi.cwiseMax(v);
    b.lo.array() -= s.radius;
    b.hi.array() += s.radius;
    return b;
}

std::vector<PieceBox> pieceBoxes(const std::vector<QueryShape>& shapes) {
    std::vector<PieceBox> out;
    out.reserve(shapes.size());
    for (const QueryShape& s : shapes) out.push_back(pieceBox(s));
    return out;
}

// A lower bound on the distance of two shapes: the distance of their boxes.
double boxGap(const PieceBox& a, const PieceBox& b) {
    return (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(0.0).stableNorm();
}

// Box gaps at or below this may still be touching pairs (kCullMarginRelative).
double cullMargin(const PieceBox& a, const PieceBox& b) {
    double m = 0;
    for (const PieceBox* x : {&a, &b})
        for (const Vec3* v : {&x->lo, &x->hi})
            for (int i = 0; i < 3; ++i)
                if (std::isfinite((*v)[i])) m = std::max(m, std::abs((*v)[i]));
    return kCullMarginRelative * m;
}

// The search in progress: its options, and the first failure (which ends it).
struct Search {
    const CompoundOptions& options;
    CompoundPairResult& out;

    bool failed() const { return out.status != CompoundStatus::Ok; }

    // Fails when pa x pb passes maxPiecePairs.
    bool piecePairsWithinLimit(const std::vector<QueryShape>& pa, const std::vector<QueryShape>& pb) {
        if (double(pa.size()) * double(pb.size()) <= options.maxPiecePairs) return true;
        out.status = CompoundStatus::WorkLimit;
        out.limitHit.which = CompoundLimit::PiecePairs;
        out.limitHit.piecesA = pa.size(), out.limitHit.piecesB = pb.size();
        out.limitHit.limit = options.maxPiecePairs;
        return false;
    }

    // Fails with the pair's status unless it is Ok.
    bool pairOk(const PairResult& r) {
        if (r.status == PairStatus::Ok) return true;
        out.status = CompoundStatus::PairFailed;
        out.pairStatus = r.status;
        return false;
    }
};

struct PairPick {
    bool found = false;
    int i = -1, j = -1;
    PairResult answer;
    long long tested = 0;
    double work = 0;  // of the pairs tested, in pairs of boxes (pairWork)
};

// A pair's GJK / EPA work in pairs of boxes (kBoxPairVertices).
double pairWork(const QueryShape& a, const QueryShape& b) {
    const auto vertices = [](const QueryShape& s) { return s.isCurved() ? 8.0 : double(s.vertices.size()); };
    return std::max(1.0, (vertices(a) + vertices(b)) / kBoxPairVertices);
}

// Counts one more pair tested; fails when the GJK work passes maxGjkWork (before the pair runs).
bool countGjkPair(Search& search, PairPick& pick, const QueryShape& a, const QueryShape& b) {
    ++pick.tested;
    pick.work += pairWork(a, b);
    if (pick.work > search.options.maxGjkWork) {
        search.out.status = CompoundStatus::WorkLimit;
        search.out.limitHit.which = CompoundLimit::GjkWork;
        search.out.limitHit.work = pick.work;
        search.out.limitHit.limit = search.options.maxGjkWork;
        return false;
    }
    return true;
}

PairResult pairOf(const QueryShape& a, const QueryShape& b, bool depth) {
    PairOptions options;
    options.depth = depth;
    return pairQuery(a, b, options);
}

// Visits the pairs whose boxes are within the touching margin, in order, with their answer
// (`wantDepth`: PairOptions::depth); the visit returns false to stop. Counts the pairs tested and
// fails before the test past maxGjkWork, or at the first failed pair.
template <class Visit>
void forEachNearPair(const std::vector<QueryShape>& a, const std::vector<QueryShape>& b, bool wantDepth, Search& search,
                     PairPick& pick, Visit&& visit) {
    const std::vector<PieceBox> ba = pieceBoxes(a), bb = pieceBoxes(b);
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j) {
            if (boxGap(ba[i], bb[j]) > cullMargin(ba[i], bb[j])) continue;
            if (!countGjkPair(search, pick, a[i], b[j])) return;
            const PairResult r = pairOf(a[i], b[j], wantDepth);
            if (!search.pairOk(r)) return;
            if (!visit(int(i), int(j), r)) return;
        }
}

// The first pair of boundary pieces that intersects (touching counts).
PairPick firstIntersecting(const std::vector<QueryShape>& a, const std::vector<QueryShape>& b, Search& search) {
    PairPick pick;
    forEachNearPair(a, b, false, search, pick, [&](int i, int j, const PairResult& ans) {
        if (ans.intersect) pick.found = true, pick.i = i, pick.j = j, pick.answer = ans;
        return !pick.found;
    });
    return pick;
}

// A point of every piece of `inner` (its core's first point, a cylinder's or cone's centre, a ray's
// origin; planes have none; a mesh's first triangle only): a piece that meets no boundary piece of
// the mesh lies wholly inside or outside it.
bool meshHoldsAPiece(const CompoundBody& outer, const CompoundBody& inner) {
    const std::size_t count = inner.mesh ? std::min<std::size_t>(1, inner.boundary.size()) : inner.boundary.size();
    for (std::size_t k = 0; k < count; ++k) {
        const QueryShape& s = inner.boundary[k];
        if (s.kind == Kind::Plane) continue;
        const Vec3 p = s.kind == Kind::Ray ? s.origin : s.isCurved() ? s.curved.center : s.vertices[0];
        // On the mesh scaled to size ~1 (exact): tiny or huge coordinates neither underflow nor
        // overflow the solid angles.
        if (std::abs(windingNumber(outer.unitMesh, scaled(p, outer.unitExponent))) > 0.5) return true;
    }
    return false;
}

// The closest pair of boundary pieces of two disjoint bodies (branch and bound on the box gaps,
// seeded with the pair whose boxes are nearest); fails before the test past maxGjkWork, or at the
// first failed pair.
PairPick closestPair(const std::vector<QueryShape>& a, const std::vector<QueryShape>& b, Search& search) {
    const std::vector<PieceBox> ba = pieceBoxes(a), bb = pieceBoxes(b);
    PairPick pick;
    double best = INFINITY;
    const auto test = [&](std::size_t i, std::size_t j) {
        if (!countGjkPair(search, pick, a[i], b[j])) return false;
        const PairResult ans = pairOf(a[i], b[j], false);
        if (!search.pairOk(ans)) return false;
        if (!pick.found || ans.distance < best) {
            best = ans.distance;
            pick.found = true, pick.i = int(i), pick.j = int(j), pick.answer = ans;
        }
        return true;
    };
    std::size_t si = 0, sj = 0;
    double nearest = INFINITY;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j)
            if (const double g = boxGap(ba[i], bb[j]); g < nearest) nearest = g, si = i, sj = j;
    if (!test(si, sj)) return pick;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j)
            if ((i != si || j != sj) && boxGap(ba[i], bb[j]) < best)
                if (!test(i, j)) return pick;
    return pick;
}

// An upper bound on the penetration depth of two shapes inside boxes a and b: the depth is the
// shortest translation that separates them, and along each axis the shorter of the two that
// separate the boxes separates the shapes too.
double depthBound(const PieceBox& a, const PieceBox& b) { return (a.hi - b.lo).cwiseMin(b.hi - a.lo).minCoeff(); }

// The deepest overlapping pair of convex pieces. Every pair whose boxes meet is a candidate; past
// maxDepthWork of candidates the query fails before any EPA runs. Candidates are visited by their
// depth bound, largest first, and the search stops when the bound (plus the rounding slack of the
// touching rule) is below the deepest depth found: the answer is the deepest pair, and among pairs
// of equal depth the first in (a, b) order, as a visit of every pair gives (hostile_query_test
// "penetration of compounds: EPA only where the box bound can beat the deepest pair, capped").
PairPick deepestPair(const std::vector<QueryShape>& a, const std::vector<QueryShape>& b, Search& search) {
    const std::vector<PieceBox> ba = pieceBoxes(a), bb = pieceBoxes(b);
    struct Candidate {
        double bound;
        int i, j;
    };
    std::vector<Candidate> candidates;
    long long count = 0;
    double work = 0, slack = 0;
    const double limit = search.options.maxDepthWork;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j) {
            const double margin = cullMargin(ba[i], bb[j]);
            if (boxGap(ba[i], bb[j]) > margin) continue;
            ++count;
            work += pairWork(a[i], b[j]);
            if (work > limit) continue;  // counted, not kept
            candidates.push_back({depthBound(ba[i], bb[j]), int(i), int(j)});
            slack = std::max(slack, margin);
        }
    PairPick pick;
    if (work > limit) {
        search.out.status = CompoundStatus::WorkLimit;
        search.out.limitHit.which = CompoundLimit::DepthWork;
        search.out.limitHit.pairs = count;
        search.out.limitHit.work = work;
        search.out.limitHit.limit = limit;
        return pick;
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& x, const Candidate& y) { return x.bound > y.bound; });
    for (const Candidate& c : candidates) {
        if (pick.found && c.bound + slack < pick.answer.depth) break;
        ++pick.tested;
        const PairResult ans = pairOf(a[std::size_t(c.i)], b[std::size_t(c.j)], true);
        if (!search.pairOk(ans)) return pick;
        if (!ans.intersect) continue;
        const bool deeper = !pick.found || ans.depth > pick.answer.depth ||
                            (ans.depth == pick.answer.depth && std::pair(c.i, c.j) < std::pair(pick.i, pick.j));
        if (deeper) pick.found = true, pick.i = c.i, pick.j = c.j, pick.answer = ans;
    }
    return pick;
}

// The pair that answered, into the result.
void setPair(CompoundPairResult& out, const PairPick& pick, CompoundPieces among) {
    out.paired = pick.found;
    out.among = among;
    out.pieceA = pick.i, out.pieceB = pick.j;
}

// A mesh's convex pieces for penetration when not yet computed (fails past the triangle limit),
// else the body's own: in `storage` or the body.
const std::vector<QueryShape>* convexPiecesOf(const CompoundBody& body, int side, std::vector<QueryShape>& storage,
                                              Search& search) {
    if (!body.mesh || !body.pieces.empty()) return &body.pieces;
    if (std::size_t(body.mesh->triangleCount()) > search.options.maxMeshTrianglesForPieces) {
        search.out.status = CompoundStatus::WorkLimit;
        search.out.limitHit.which = CompoundLimit::MeshTriangles;
        search.out.limitHit.body = side;
        search.out.limitHit.triangles = std::size_t(body.mesh->triangleCount());
        search.out.limitHit.limit = double(search.options.maxMeshTrianglesForPieces);
        return nullptr;
    }
    storage = meshConvexPieces(body);
    return &storage;
}

}  // namespace

CompoundPairResult compoundPairQuery(const CompoundBody& a, const CompoundBody& b, CompoundOp op,
                                     const CompoundOptions& options) {
    CompoundPairResult out;
    Search search{options, out};
    out.boundaryPieces = {a.boundary.size(), b.boundary.size()};
    out.convexPieces = {a.pieces.size(), b.pieces.size()};
    if (!search.piecePairsWithinLimit(a.boundary, b.boundary)) return out;

    // Intersect: a pair of boundary pieces meets, or a mesh holds a piece of the other body.
    const PairPick hit = firstIntersecting(a.boundary, b.boundary, search);
    if (search.failed()) return out;
    out.pairsTested = hit.tested;
    out.intersect = hit.found || (a.mesh && meshHoldsAPiece(a, b)) || (b.mesh && meshHoldsAPiece(b, a));
    if (op == CompoundOp::Intersect) {
        setPair(out, hit, CompoundPieces::Boundary);
        return out;
    }
    if (!out.intersect) {
        const PairPick c = closestPair(a.boundary, b.boundary, search);
        if (search.failed()) return out;
        out.pairsTested += c.tested;
        const PairResult& s = c.answer;
        out.distance = s.distance;
        out.normal = s.normal, out.pointA = s.pointA, out.pointB = s.pointB;
        out.hasWitness = true;
        setPair(out, c, CompoundPieces::Boundary);
        return out;
    }
    if (op == CompoundOp::Distance) {
        out.distance = 0.0;
        setPair(out, hit, CompoundPieces::Boundary);
        return out;
    }
    // Penetration: the deepest pair of convex pieces; a touching contact no piece pair reaches
    // (rounding at a cell's cut) is answered by the deepest pair of boundary pieces.
    std::vector<QueryShape> meshPiecesA, meshPiecesB;
    const std::vector<QueryShape>* piecesA = convexPiecesOf(a, 0, meshPiecesA, search);
    if (!piecesA) return out;
    const std::vector<QueryShape>* piecesB = convexPiecesOf(b, 1, meshPiecesB, search);
    if (!piecesB) return out;
    out.convexPieces = {piecesA->size(), piecesB->size()};
    if (!search.piecePairsWithinLimit(*piecesA, *piecesB)) return out;
    PairPick deep = deepestPair(*piecesA, *piecesB, search);
    if (search.failed()) return out;
    out.pairsTested += deep.tested;
    CompoundPieces among = CompoundPieces::Convex;
    if (!deep.found) {
        deep = deepestPair(a.boundary, b.boundary, search);
        if (search.failed()) return out;
        out.pairsTested += deep.tested;
        among = CompoundPieces::Boundary;
    }
    if (!deep.found) {
        out.status = CompoundStatus::NoPiecePair;
        return out;
    }
    const PairResult& s = deep.answer;
    out.depth = s.depth;
    out.normal = s.normal, out.pointA = s.pointA, out.pointB = s.pointB;
    out.hasWitness = true;
    setPair(out, deep, among);
    return out;
}

}  // namespace cdlab
