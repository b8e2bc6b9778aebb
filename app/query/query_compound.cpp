// The compound and mesh ops of `cdlab query` (app/query/query_compound.h): the query's JSON read
// into core's compound bodies and pair query (core/query/compound.h), and its result, trace and
// failures written back as JSON and errors at the JSON node of each.
#include "app/query/query_compound.h"

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/query/query_json.h"
#include "app/query/query_shapes.h"
#include "core/geometry/solid_mesh.h"
#include "core/query/compound.h"

namespace cdlab::demos {

namespace {

// ---------------------------------------------------------------------------------------------
// Parsing.

std::string edgeText(const std::array<int, 2>& e) {
    return "(" + std::to_string(e[0]) + ", " + std::to_string(e[1]) + ")";
}

// {"vertices", "triangles"[, "position", "rotation"]}: the world-frame mesh, checked closed and
// consistently oriented; an inward-facing mesh is turned outward (it bounds the same solid).
CompoundBody parseMesh(const JsonNode& body) {
    ObjectReader r(body);
    JsonNode vn = r.get("vertices");
    const std::vector<Vec3> local = vn.asVec3List();
    if (local.size() < 4) vn.fail("a closed mesh needs at least 4 vertices, got " + std::to_string(local.size()));
    if (local.size() > std::size_t(std::numeric_limits<int>::max())) vn.fail("too many vertices");
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
            at(check.triangle)
                .fail("the mesh is not closed: edge " + edgeText(check.edge) +
                      " of this triangle is in no other triangle as " + edgeText({check.edge[1], check.edge[0]}));
        case SolidMeshStatus::InconsistentOrientation:
            at(check.triangle)
                .fail("edge " + edgeText(check.edge) +
                      " is in this and an earlier triangle in the same direction: the triangles are "
                      "not consistently oriented (or more than two meet at the edge)");
    }
    std::optional<CompoundBody> solid = CompoundBody::solidMesh(std::move(mesh));
    if (!solid) tn.fail("the mesh encloses no volume (all its triangles are flat against each other)");
    return std::move(*solid);
}

CompoundBody parseBody(const JsonNode& node) {
    if (!isCompoundOrMesh(node)) return CompoundBody::shape(parseQueryShape(node));
    const std::string key = node.raw().begin().key();
    const JsonNode inner(node.raw().begin().value(), node.path() + "." + key, node.source());
    if (key == "mesh") return parseMesh(inner);
    if (!inner.isArray() || inner.size() == 0)
        inner.fail("expected a non-empty list of convex shapes, got " + JsonNode::describe(inner.raw()));
    std::vector<QueryShape> shapes;
    for (const JsonNode& item : inner.items()) {
        if (isCompoundOrMesh(item))
            item.fail(
                "a compound's pieces are convex shapes: list a nested compound's shapes directly; a mesh "
                "cannot be a piece");
        QueryShape s = parseQueryShape(item);
        if (!s.bounded()) item.fail("a compound's pieces are bounded convex shapes (not a plane or a ray)");
        shapes.push_back(std::move(s));
    }
    return CompoundBody::compound(std::move(shapes));
}

// ---------------------------------------------------------------------------------------------
// Failures and answers.

std::string limitText(double limit) { return std::to_string(static_cast<long long>(limit)); }

// The query's error for a failed compound query: a work limit at `an` (a mesh's triangles at its
// own body's node), a failed piece pair as a failed convex pair's (query_ops.cpp's requireOk).
[[noreturn]] void failCompound(const CompoundPairResult& r, const JsonNode& an, const JsonNode& bn) {
    const CompoundLimitHit& h = r.limitHit;
    switch (r.status) {
        case CompoundStatus::Ok: break;
        case CompoundStatus::PairFailed: throw InputError(std::string("query: ") + describe(r.pairStatus));
        case CompoundStatus::NoPiecePair:
            an.fail(
                "penetration: the bodies overlap but no pair of their convex pieces does (a piece lost to rounding)");
        case CompoundStatus::WorkLimit:
            switch (h.which) {
                case CompoundLimit::PiecePairs:
                    an.fail("the bodies have " + std::to_string(h.piecesA) + " x " + std::to_string(h.piecesB) +
                            " piece pairs, above the limit of " + limitText(h.limit));
                case CompoundLimit::GjkWork:
                    an.fail("the search needs GJK on more than " + limitText(h.limit) +
                            " pairs of boxes' work (pieces whose boxes meet; a piece of n vertices counts n / 16 "
                            "boxes), the limit (about a second)");
                case CompoundLimit::DepthWork:
                    an.fail("penetration runs EPA on the pairs of pieces whose boxes meet: " + std::to_string(h.pairs) +
                            " pairs, " + std::to_string(static_cast<long long>(h.work)) +
                            " pairs of boxes' work (a piece of n vertices counts n / 16 boxes), above the limit of " +
                            limitText(h.limit) + " (about a second)");
                case CompoundLimit::MeshTriangles:
                    (h.body == 0 ? an : bn)
                        .fail("penetration decomposes a mesh into convex pieces and takes at most " +
                              limitText(h.limit) + " triangles, got " + std::to_string(h.triangles) +
                              " (intersect and distance take more)");
            }
    }
    throw InputError("query: compound query failed");  // not reached: every status is answered above
}

const char* kindName(CompoundBody::Kind kind) {
    switch (kind) {
        case CompoundBody::Kind::Compound: return "compound";
        case CompoundBody::Kind::Mesh: return "mesh";
        case CompoundBody::Kind::Shape: break;
    }
    return "shape";
}

Json traceJson(const CompoundBody& a, const CompoundBody& b, const CompoundPairResult& r) {
    const auto side = [&](const CompoundBody& x, int k) {
        Json j = {{"kind", kindName(x.kind)}, {"boundary_pieces", r.boundaryPieces[std::size_t(k)]}};
        if (x.mesh) j["convex_pieces"] = r.convexPieces[std::size_t(k)];
        return j;
    };
    Json t = {{"algorithm", "compound"}, {"a", side(a, 0)}, {"b", side(b, 1)}, {"pairs_tested", r.pairsTested}};
    if (r.paired)
        t["pair"] = {{"among", r.among == CompoundPieces::Convex ? "convex_pieces" : "boundary"},
                     {"a", r.pieceA},
                     {"b", r.pieceB}};
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
    const CompoundBody a = parseBody(an), b = parseBody(bn);
    const CompoundOp cop = op == "intersect"  ? CompoundOp::Intersect
                           : op == "distance" ? CompoundOp::Distance
                                              : CompoundOp::Penetration;
    const CompoundPairResult s = compoundPairQuery(a, b, cop);
    if (s.status != CompoundStatus::Ok) failCompound(s, an, bn);
    Json out;
    if (op == "intersect") {
        out = {{"intersect", s.intersect}};
    } else if (!s.intersect) {
        out = {{"intersect", false}, {"distance", s.distance}};
        if (op == "penetration") out["normal"] = vecJson(s.normal);
        out["point_a"] = vecJson(s.pointA);
        out["point_b"] = vecJson(s.pointB);
    } else if (op == "distance") {
        out = {{"intersect", true}, {"distance", 0.0}};
    } else {
        out = {{"intersect", true},
               {"depth", s.depth},
               {"normal", vecJson(s.normal)},
               {"point_a", vecJson(s.pointA)},
               {"point_b", vecJson(s.pointB)}};
    }
    if (wantTrace) out["trace"] = traceJson(a, b, s);
    return out;
}

}  // namespace cdlab::demos
