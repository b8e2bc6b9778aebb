// A query plane n·x = d against a bounded shape in closed form: the span of the shape's signed
// distances to the plane (its support values along ±n̂), shared by the pair ops and the casts.
#pragma once

#include "core/base/types.h"
#include "app/query/query_shapes.h"

namespace cdlab::demos {

/// n̂·x = d̂ with |n̂| = 1 (the parser keeps |normal| in [0.5, sqrt 3], so this neither under- nor overflows).
struct UnitPlane {
    Vec3 n;
    double d;
};
UnitPlane unitPlane(const QueryShape& plane);

struct PlaneSpan {
    double lo, hi;             // min / max of (n·x - d)/|n| over the shape
    Vec3 lowPoint, highPoint;  // shape points attaining them
    double touch;              // the touching tolerance of this plane and shape
};
PlaneSpan planeSpan(const QueryShape& plane, const QueryShape& s);

}  // namespace cdlab::demos
