"""The reference solution of plane.py's TODO (kept out of the handout: examples/student/README.md).
python3 plane_solution.py < ../cases/plane.jsonl | ../../../cdlab check   ->  all pass"""
import math

import plane
from kit import dot, neg, run, scale, sub


def contact(body, normal, offset):
    unit = scale(1 / math.sqrt(dot(normal, normal)), normal)
    heights = sorted((dot(unit, v) - offset / math.sqrt(dot(normal, normal)), v) for v in body)
    lowest, v = heights[0]
    if lowest > 0:
        return {"colliding": False, "distance": lowest, "normal": neg(unit),
                "closest": [{"point_a": v, "point_b": sub(v, scale(lowest, unit))}]}
    points = [{"point_a": p, "point_b": sub(p, scale(h, unit)), "depth": -h}
              for h, p in heights[:plane.MAX_POINTS] if h <= 0]
    return {"colliding": True, "depth": -lowest, "normal": neg(unit), "points": points}


plane.contact = contact

if __name__ == "__main__":
    run(plane.solve)
