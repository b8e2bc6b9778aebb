#include "app/query/query_compound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/solid_mesh.h"
#include "core/spatial/convex_decomposition.h"
#include "app/query/query_json.h"
#include "app/query/query_limits.h"
#include "app/query/query_ops.h"
#include "app/query/query_shapes.h"

namespace cdlab::demos {

namespace {

using Kind = QueryShape::Kind;

// One side of the query. The closest points of two disjoint bodies lie on their boundary pieces;
// the deepest pair is sought among their convex pieces; a mesh also answers "is this point inside".
struct Body {
    const char* kind = "shape";         // "shape", "compound" or "mesh"
    std::vector<QueryShape> boundary;   // a compound's shapes, a mesh's triangles, or the one shape
    std::vector<QueryShape> pieces;     // convex pieces (a mesh's: its BSP cells, built on demand)
    std::optional<TriangleMesh> mesh;   // world frame, outward-facing
    TriangleMesh unitMesh;              // the mesh times 2^unitExponent: size ~1 (containment tests)
    int unitExponent = 0;
    std::optional<JsonNode> node;
};

// ---------------------------------------------------------------------------------------------
// Parsing.

QueryShape triangleShape(const Triangle& t) {
    QueryShape s;
    s.kind = Kind::Triangle;
    s.vertices = {t.a, t.b, t.c};
    return s;
}

std::string edgeText(const std::array<int, 2>& e) {
    return "(" + std::to_string(e[0]) + ", " + std::to_string(e[1]) + ")";
}

// {"vertices", "triangles"[, "position", "rotation"]}: the world-frame mesh, checked closed and
// consistently oriented; an inward-facing mesh is turned outward (it bounds the same solid).
TriangleMesh parseMesh(const JsonNode& body, TriangleMesh& unit, int& unitExponent) {
    ObjectReader r(body);
    JsonNode vn = r.get("vertices");
    const std::vector<Vec3> local = vn.asVec3List();
    if (local.size() < 4) vn.fail("a closed mesh needs at least 4 vertices, got " + std::to_string(local.size()));
    if (local.size() > std::size_t(std::numeric_limits<int>::max()))
        vn.fail("too many vertices");
    JsonNode tn = r.get("triangles");
    if (!tn.isArray()) tn.fail("expected [[i, j, k], ...], got " + JsonNode::describe(tn.raw()));
    TriangleMesh mesh;
    const int last = int(local.size()) - 1;
    for (const JsonNode& t : tn.items()) {
        if (!t.isArray() || t.size() != 3) t.fail("expected a triangle [i, j, k] of vertex indices");
        mesh.triangles.push_back({t.at(0).asInt(0, last), t.at(1).asInt(0, last), t.at(2).asInt(0, last)});
    }
    Transform pose;
    if (auto p = r.find("position")) pose.position = p->asVec3();
    if (auto q = r.find("rotation")) pose.rotation = q->asQuat();
    r.finish();
    const Mat3 R = pose.rotation.toRotationMatrix();
    for (const Vec3& v : local) {
        mesh.vertices.push_back(R * v + pose.position);
        if (!mesh.vertices.back().allFinite()) vn.fail("mesh coordinates overflow after transformation");
    }

    const SolidMeshCheck check = checkSolidMesh(mesh);
    const auto at = [&](int t) { return tn.at(std::size_t(t)); };
    switch (check.status) {
        case SolidMeshStatus::Closed: break;
        case SolidMeshStatus::TooFewTriangles:
            tn.fail("a closed mesh needs at least 4 triangles, got " + std::to_string(mesh.triangles.size()));
        case SolidMeshStatus::RepeatedVertex:
            at(check.triangle).fail("the triangle names vertex " + std::to_string(check.edge[0]) + " twice");
        case SolidMeshStatus::OpenEdge:
            at(check.triangle).fail("the mesh is not closed: edge " + edgeText(check.edge) +
                                    " of this triangle is in no other triangle as " +
                                    edgeText({check.edge[1], check.edge[0]}));
        case SolidMeshStatus::InconsistentOrientation:
            at(check.triangle).fail("edge " + edgeText(check.edge) +
                                    " is in this and an earlier triangle in the same direction: the triangles are "
                                    "not consistently oriented (or more than two meet at the edge)");
    }
    Vec3 lo = mesh.vertices[0], hi = lo;
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    // The volume of the mesh scaled by a power of two to a size of ~1 (exact): 1e-300 or 1e300
    // meshes neither underflow nor overflow the cubes. Rounding of the sum is ~1e-16 per triangle;
    // a solid is far above 1e-12.
    int e = 0;
    std::frexp(std::max((hi - lo).maxCoeff(), (0.5 * (hi + lo)).cwiseAbs().maxCoeff()), &e);
    unitExponent = -e;
    unit = mesh;
    for (Vec3& v : unit.vertices) v = scaled(v, -e);
    const double size = std::ldexp((hi - lo).maxCoeff(), -e);
    const double volume = signedVolume(unit);
    if (!(std::abs(volume) > 1e-12 * size * size * size))
        tn.fail("the mesh encloses no volume (all its triangles are flat against each other)");
    if (volume < 0) {
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
        unit.triangles = mesh.triangles;
    }
    return mesh;
}

Body parseBody(const JsonNode& node) {
    Body body;
    body.node = node;
    if (!isCompoundOrMesh(node)) {
        body.boundary = {parseQueryShape(node)};
        body.pieces = body.boundary;
        return body;
    }
    const std::string key = node.raw().begin().key();
    const JsonNode inner(node.raw().begin().value(), node.path() + "." + key, node.source());
    if (key == "mesh") {
        body.kind = "mesh";
        body.mesh = parseMesh(inner, body.unitMesh, body.unitExponent);
        for (int t = 0; t < body.mesh->triangleCount(); ++t) body.boundary.push_back(triangleShape(body.mesh->triangle(t)));
        return body;
    }
    body.kind = "compound";
    if (!inner.isArray() || inner.size() == 0)
        inner.fail("expected a non-empty list of convex shapes, got " + JsonNode::describe(inner.raw()));
    for (const JsonNode& item : inner.items()) {
        if (isCompoundOrMesh(item))
            item.fail("a compound's pieces are convex shapes: list a nested compound's shapes directly; a mesh "
                      "cannot be a piece");
        QueryShape s = parseQueryShape(item);
        if (!s.bounded()) item.fail("a compound's pieces are bounded convex shapes (not a plane or a ray)");
        body.boundary.push_back(std::move(s));
    }
    body.pieces = body.boundary;
    return body;
}

// A mesh's convex pieces, built when a penetration needs them.
void ensurePieces(Body& body) {
    if (!body.mesh || !body.pieces.empty()) return;
    if (std::size_t(body.mesh->triangleCount()) > kMaxMeshTrianglesForPieces)
        body.node->fail("penetration decomposes a mesh into convex pieces and takes at most " +
                        std::to_string(kMaxMeshTrianglesForPieces) + " triangles, got " +
                        std::to_string(body.mesh->triangleCount()) + " (intersect and distance take more)");
    BspOptions options;
    // Scoring every triangle at every node is quadratic; 32 evenly spaced candidates (Ericson §8.3.2)
    // give as many pieces on a torus (4273 vs 4210 of 10 000 triangles) in a tenth of the time (0.3 s).
    options.maxCandidates = 32;
    // On the mesh scaled to size ~1 (exact), so that 1e-300 or 1e300 meshes neither underflow nor
    // overflow the cells' volumes; the corners are scaled back.
    const ConvexDecomposition d = decomposeIntoConvexPieces(body.unitMesh, options);
    for (const std::vector<Vec3>& corners : d.pieces) {
        QueryShape s;
        s.kind = Kind::Polytope;
        for (const Vec3& c : corners) s.vertices.push_back(scaled(c, -body.unitExponent));
        body.pieces.push_back(std::move(s));
    }
}

// ---------------------------------------------------------------------------------------------
// Pairs of pieces, culled by their bounding boxes.

struct Box {
    Vec3 lo, hi;
};

Box boxOf(const QueryShape& s) {
    if (!s.bounded()) return {Vec3::Constant(-INFINITY), Vec3::Constant(INFINITY)};
    if (s.isCurved()) {
        Box b;
        s.curved.bounds(b.lo, b.hi);
        return b;
    }
    Box b{s.vertices[0], s.vertices[0]};
    for (const Vec3& v : s.vertices) b.lo = b.lo.cwiseMin(v), b.hi = b.hi.cwiseMax(v);
    b.lo.array() -= s.radius;
    b.hi.array() += s.radius;
    return b;
}

std::vector<Box> boxesOf(const std::vector<QueryShape>& shapes) {
    std::vector<Box> out;
    out.reserve(shapes.size());
    for (const QueryShape& s : shapes) out.push_back(boxOf(s));
    return out;
}

// A lower bound on the distance of two shapes: the distance of their boxes.
double boxGap(const Box& a, const Box& b) { return (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(0.0).stableNorm(); }

// Box gaps at or below this may still be touching pairs: far above the rounding of the gap and of
// the touching rule (1e-13 of the pair's extent, core/base/touch_rule.h).
double cullMargin(const Box& a, const Box& b) {
    double m = 0;
    for (const Box* x : {&a, &b})
        for (const Vec3* v : {&x->lo, &x->hi})
            for (int i = 0; i < 3; ++i)
                if (std::isfinite((*v)[i])) m = std::max(m, std::abs((*v)[i]));
    return 1e-9 * m;
}

void requirePairsWithinLimit(const Body& a, const Body& b, const std::vector<QueryShape>& pa,
                             const std::vector<QueryShape>& pb) {
    if (double(pa.size()) * double(pb.size()) > kMaxCompoundPairs)
        a.node->fail("the bodies have " + std::to_string(pa.size()) + " x " + std::to_string(pb.size()) +
                     " piece pairs, above the limit of " + std::to_string(static_cast<long long>(kMaxCompoundPairs)));
    (void)b;
}

struct PairPick {
    bool found = false;
    int i = -1, j = -1;
    ShapePairAnswer answer;
    long long tested = 0;
    double work = 0;  // of the pairs tested, in pairs of boxes (pairWork)
};

// A pair's GJK / EPA work in pairs of boxes (kBoxPairVertices).
double pairWork(const QueryShape& a, const QueryShape& b) {
    const auto vertices = [](const QueryShape& s) { return s.isCurved() ? 8.0 : double(s.vertices.size()); };
    return std::max(1.0, (vertices(a) + vertices(b)) / kBoxPairVertices);
}

// Counts one more pair tested; fails at `node` when the GJK work passes kMaxCompoundGjkPairs.
void countGjkPair(const JsonNode& node, PairPick& pick, const QueryShape& a, const QueryShape& b) {
    ++pick.tested;
    pick.work += pairWork(a, b);
    if (pick.work > kMaxCompoundGjkPairs)
        node.fail("the search needs GJK on more than " + std::to_string(static_cast<long long>(kMaxCompoundGjkPairs)) +
                  " pairs of boxes' work (pieces whose boxes meet; a piece of n vertices counts n / 16 boxes), the "
                  "limit (about a second)");
}

// Visits the pairs whose boxes are within the touching margin, in order, with their answer
// (`wantDepth` as in shapePairAnswer); the visit returns false to stop. Counts the pairs tested and
// fails at `node` before the test past kMaxCompoundGjkPairs.
template <class Visit>
void forEachNearPair(const std::vector<QueryShape>& a, const std::vector<QueryShape>& b, bool wantDepth,
                     const JsonNode& node, PairPick& pick, Visit&& visit) {
    const std::vector<Box> ba = boxesOf(a), bb = boxesOf(b);
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j) {
            if (boxGap(ba[i], bb[j]) > cullMargin(ba[i], bb[j])) continue;
            countGjkPair(node, pick, a[i], b[j]);
            if (!visit(int(i), int(j), shapePairAnswer(a[i], b[j], wantDepth))) return;
        }
}

// The first pair of boundary pieces that intersects (touching counts).
PairPick firstIntersecting(const std::vector<QueryShape>& a, const std::vector<QueryShape>& b, const JsonNode& node) {
    PairPick pick;
    forEachNearPair(a, b, false, node, pick, [&](int i, int j, const ShapePairAnswer& ans) {
        if (ans.intersect) pick.found = true, pick.i = i, pick.j = j, pick.answer = ans;
        return !pick.found;
    });
    return pick;
}

// A point of every piece of `inner` (its core's first point, a cylinder's or cone's centre, a ray's
// origin; planes have none): a piece that meets no boundary piece of the mesh lies wholly inside or
// outside it.
bool meshHoldsAPiece(const Body& outer, const Body& inner) {
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
// seeded with the pair whose boxes are nearest); fails at `node` before the test past
// kMaxCompoundGjkPairs.
PairPick closestPair(const std::vector<QueryShape>& a, const std::vector<QueryShape>& b, const JsonNode& node) {
    const std::vector<Box> ba = boxesOf(a), bb = boxesOf(b);
    PairPick pick;
    double best = INFINITY;
    const auto test = [&](std::size_t i, std::size_t j) {
        countGjkPair(node, pick, a[i], b[j]);
        const ShapePairAnswer ans = shapePairAnswer(a[i], b[j], false);
        if (!pick.found || ans.distance < best) {
            best = ans.distance;
            pick.found = true, pick.i = int(i), pick.j = int(j), pick.answer = ans;
        }
    };
    std::size_t si = 0, sj = 0;
    double nearest = INFINITY;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j)
            if (const double g = boxGap(ba[i], bb[j]); g < nearest) nearest = g, si = i, sj = j;
    test(si, sj);
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j)
            if ((i != si || j != sj) && boxGap(ba[i], bb[j]) < best) test(i, j);
    return pick;
}

// An upper bound on the penetration depth of two shapes inside boxes a and b: the depth is the
// shortest translation that separates them, and along each axis the shorter of the two that
// separate the boxes separates the shapes too.
double depthBound(const Box& a, const Box& b) { return (a.hi - b.lo).cwiseMin(b.hi - a.lo).minCoeff(); }

// The deepest overlapping pair of convex pieces. Every pair whose boxes meet is a candidate; past
// kMaxCompoundDepthPairs candidates the query fails at `node` before any EPA runs. Candidates are
// visited by their depth bound, largest first, and the search stops when the bound (plus the
// rounding slack of the touching rule) is below the deepest depth found: the answer is the deepest
// pair, and among pairs of equal depth the first in (a, b) order, as a visit of every pair gives.
PairPick deepestPair(const std::vector<QueryShape>& a, const std::vector<QueryShape>& b, const JsonNode& node) {
    const std::vector<Box> ba = boxesOf(a), bb = boxesOf(b);
    struct Candidate {
        double bound;
        int i, j;
    };
    std::vector<Candidate> candidates;
    long long count = 0;
    double work = 0, slack = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j) {
            const double margin = cullMargin(ba[i], bb[j]);
            if (boxGap(ba[i], bb[j]) > margin) continue;
            ++count;
            work += pairWork(a[i], b[j]);
            if (work > kMaxCompoundDepthPairs) continue;  // counted, not kept
            candidates.push_back({depthBound(ba[i], bb[j]), int(i), int(j)});
            slack = std::max(slack, margin);
        }
    if (work > kMaxCompoundDepthPairs)
        node.fail("penetration runs EPA on the pairs of pieces whose boxes meet: " + std::to_string(count) + " pairs, " +
                  std::to_string(static_cast<long long>(work)) +
                  " pairs of boxes' work (a piece of n vertices counts n / 16 boxes), above the limit of " +
                  std::to_string(static_cast<long long>(kMaxCompoundDepthPairs)) + " (about a second)");
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& x, const Candidate& y) { return x.bound > y.bound; });
    PairPick pick;
    for (const Candidate& c : candidates) {
        if (pick.found && c.bound + slack < pick.answer.depth) break;
        ++pick.tested;
        const ShapePairAnswer ans = shapePairAnswer(a[std::size_t(c.i)], b[std::size_t(c.j)], true);
        if (!ans.intersect) continue;
        const bool deeper = !pick.found || ans.depth > pick.answer.depth ||
                            (ans.depth == pick.answer.depth && std::pair(c.i, c.j) < std::pair(pick.i, pick.j));
        if (deeper) pick.found = true, pick.i = c.i, pick.j = c.j, pick.answer = ans;
    }
    return pick;
}

Json traceJson(const Body& a, const Body& b, const PairPick& pick, const char* among, long long tested) {
    const auto side = [](const Body& x) {
        Json j = {{"kind", x.kind}, {"boundary_pieces", x.boundary.size()}};
        if (x.mesh) j["convex_pieces"] = x.pieces.size();
        return j;
    };
    Json t = {{"algorithm", "compound"}, {"a", side(a)}, {"b", side(b)}, {"pairs_tested", tested}};
    if (pick.found) t["pair"] = {{"among", among}, {"a", pick.i}, {"b", pick.j}};
    return t;
}

}  // namespace

bool isCompoundOrMesh(const JsonNode& shape) {
    if (!shape.isObject() || shape.raw().size() != 1) return false;
    const std::string& key = shape.raw().begin().key();
    return key == "compound" || key == "mesh";
}

Json answerCompoundQuery(const std::string& op, ObjectReader& r, const JsonNode& an, const JsonNode& bn) {
    if (auto m = r.find("method")) m->asEnum({"gjk"});  // per-pair GJK / EPA; the feature walks take convex shapes
    const bool wantTrace = r.boolOr("trace", false);
    r.finish();
    Body a = parseBody(an), b = parseBody(bn);
    requirePairsWithinLimit(a, b, a.boundary, b.boundary);

    // Intersect: a pair of boundary pieces meets, or a mesh holds a piece of the other body.
    PairPick hit = firstIntersecting(a.boundary, b.boundary, an);
    long long tested = hit.tested;
    const bool intersect = hit.found || (a.mesh && meshHoldsAPiece(a, b)) || (b.mesh && meshHoldsAPiece(b, a));
    Json out;
    if (op == "intersect") {
        out = {{"intersect", intersect}};
        if (wantTrace) out["trace"] = traceJson(a, b, hit, "boundary", tested);
        return out;
    }
    if (!intersect) {
        const PairPick c = closestPair(a.boundary, b.boundary, an);
        tested += c.tested;
        const ShapePairAnswer& s = c.answer;
        out = {{"intersect", false}, {"distance", s.distance}};
        if (op == "penetration") out["normal"] = vecJson(s.normal);
        out["point_a"] = vecJson(s.pointA);
        out["point_b"] = vecJson(s.pointB);
        if (wantTrace) out["trace"] = traceJson(a, b, c, "boundary", tested);
        return out;
    }
    if (op == "distance") {
        out = {{"intersect", true}, {"distance", 0.0}};
        if (wantTrace) out["trace"] = traceJson(a, b, hit, "boundary", tested);
        return out;
    }
    // Penetration: the deepest pair of convex pieces; a touching contact no piece pair reaches
    // (rounding at a cell's cut) is answered by the deepest pair of boundary pieces.
    ensurePieces(a);
    ensurePieces(b);
    requirePairsWithinLimit(a, b, a.pieces, b.pieces);
    PairPick deep = deepestPair(a.pieces, b.pieces, an);
    tested += deep.tested;
    const char* among = "convex_pieces";
    if (!deep.found) {
        deep = deepestPair(a.boundary, b.boundary, an);
        tested += deep.tested;
        among = "boundary";
    }
    if (!deep.found)
        an.fail("penetration: the bodies overlap but no pair of their convex pieces does (a piece lost to rounding)");
    const ShapePairAnswer& s = deep.answer;
    out = {{"intersect", true},
           {"depth", s.depth},
           {"normal", vecJson(s.normal)},
           {"point_a", vecJson(s.pointA)},
           {"point_b", vecJson(s.pointB)}};
    if (wantTrace) out["trace"] = traceJson(a, b, deep, among, tested);
    return out;
}

}  // namespace cdlab::demos
