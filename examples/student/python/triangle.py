"""Assignment item: the point of a triangle nearest a point p, and the Voronoi region it lies in
(Ericson, Real-Time Collision Detection §5.1.5; the course's "closest point on triangle").

    python3 triangle.py < ../cases/triangle.jsonl | ../../../cdlab check

Each case is a `closest_point_triangle` query; you answer {"point": q, "region": r} and trace the
region tests you made, in order, so that `cdlab check` can name the first one that went wrong
(docs/check.md, "Voronoi-region trace schema")."""
from kit import add, dot, run, scale, sub


def test(tests, region, terms, accepted):
    """Records one region test: its name, the terms it read (name -> value) and its decision."""
    tests.append({"region": region, "terms": [{"name": n, "value": v} for n, v in terms.items()],
                  "accepted": accepted})
    return accepted


def closest_point_triangle(p, a, b, c):
    """Returns (q, region, (u, v, w), tests): q = u·a + v·b + w·c is the point of triangle abc
    nearest p, region one of A, B, C, AB, BC, CA, ABC, and tests the region tests made."""
    tests = []
    ab, ac, ap = sub(b, a), sub(c, a), sub(p, a)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    if test(tests, "A", {"d1": d1, "d2": d2}, d1 <= 0 and d2 <= 0):
        return a, "A", (1.0, 0.0, 0.0), tests
    # TODO: the regions of vertex B, edge AB, vertex C, edge AC and edge BC, in that order, each
    # recorded with test() as vertex A's is above (terms d3..d6 and va, vb, vc, named as Ericson
    # names them). `cdlab check` says "test 1 (ABC): accepted, but the point lies outside this
    # region" until they are here.
    # The face region: p projects inside the triangle (va, vb, vc >= 0).
    test(tests, "ABC", {}, True)
    n = (ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0])
    q = sub(p, scale(dot(ap, n) / dot(n, n), n))
    return q, "ABC", (1 / 3, 1 / 3, 1 / 3), tests


def solve(case):
    a, b, c = (tuple(v) for v in case["triangle"])
    q, region, _, tests = closest_point_triangle(tuple(case["point"]), a, b, c)
    return {"point": q, "region": region}, {"algorithm": "ericson_regions", "tests": tests}


if __name__ == "__main__":
    run(solve)
