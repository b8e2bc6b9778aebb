// What `cdlab check` measures answers with (app/check/check.cpp, app/check/trace_check.cpp):
// number formatting for verdicts, JSON vectors, lengths that neither overflow nor underflow, the
// size of a problem (for tolerances), the query's shapes read once per line (support values and
// distances by cdlab's own query code), and the escaping of verdict lines.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "app/query/query_shapes.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// A difference or a tolerance: three digits say enough.
std::string num(double x);
/// A value: enough digits to show where two answers part.
std::string value(double x);

bool isVec(const Json& j);
/// The vector [x, y, z]; throws std::invalid_argument when j is not one (isVec).
Vec3 vec(const Json& j);

/// |v|, scaled by the largest |component| first: exact to rounding for every finite v, also where
/// the squared norm overflows (components >= 1e154) or underflows (<= 1e-154). 0 for 0, inf for an
/// infinite component, NaN for a NaN one.
double length(const Vec3& v);
/// v / |v| by the same scaling (the zero vector and non-finite ones are returned as they are).
Vec3 unit(const Vec3& v);

/// The member `key` of the object j, or nullptr (j not an object, or no such key): the one way
/// app/check reads a key of a JSON object it did not build, never const operator[] (undefined
/// for a missing key).
const Json* member(const Json& j, const std::string& key);
/// The number member `key` of j, or nothing.
std::optional<double> numberMember(const Json& j, const std::string& key);
/// The [x, y, z] member `key` of j, or nothing.
std::optional<Vec3> vecMember(const Json& j, const std::string& key);

/// A string of yours echoed in a reason: at most 60 bytes, longer ones cut with "...".
std::string shortText(const std::string& s);

/// The size of the problem: the extent of every point of the query's shapes (radii count twice),
/// and their largest coordinate (whose rounding no answer can beat). Directions (a ray's, a
/// plane's normal, "initial_direction") are not points: their length is arbitrary.
class ShapeModel;

struct Size {
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    double radius = 0, largest = 0;
    void add(const Json& j, const std::string& key = "");
    /// The box of a bounded shape from its support values: a cylinder's half_height or a cone's
    /// height is no point of the query, yet sets its size (check_test "a curved shape's size
    /// counts"). Unbounded shapes and unreadable ones add nothing.
    void addBox(const ShapeModel& shape);
    /// relative x the extent, plus 16 ulps of the largest coordinate.
    double tolerance(double relative) const;
};

/// A query shape read once (a line's "a", "b" or "shape"), so that support values and distances,
/// asked for at every trace step, cost no JSON parse each. Unreadable shapes answer nothing.
class ShapeModel {
public:
    ShapeModel() = default;
    explicit ShapeModel(const Json& shape);

    /// Support value h_S(n) = max over S of x·n (a compound: its pieces; a mesh: its vertices);
    /// nothing for unbounded shapes or what cannot be read.
    std::optional<double> support(const Vec3& n) const;
    /// The vertices of a shape that is their hull (polytope, box, triangle, segment, point, mesh);
    /// nothing for rounded, curved, unbounded or compound shapes.
    const std::vector<Vec3>* vertices() const;
    /// Distance from a point to the shape by cdlab's own distance op (0 inside); nothing when the
    /// shape cannot be read.
    std::optional<double> distanceTo(const Vec3& p) const;
    /// The shape's point nearest p (p itself inside) by the same op; nothing for a compound or a
    /// mesh, or when the shape cannot be read.
    std::optional<Vec3> closestPointTo(const Vec3& p) const;

private:
    enum class Form { None, Shape, Compound, Mesh };
    Form form_ = Form::None;
    QueryShape shape_;                 // Form::Shape
    std::vector<ShapeModel> pieces_;   // Form::Compound
    std::vector<Vec3> meshVertices_;   // Form::Mesh, posed
    std::shared_ptr<const std::string> text_;  // Compound, Mesh: the shape's JSON for the distance op
};

}  // namespace cdlab::demos
