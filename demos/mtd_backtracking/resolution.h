// The numbers of the mtd_backtracking demo: a still polygon A, a polygon B moving (and turning) over
// t in [0, 1] and penetrating A at t = 1, and the three corrections of that end pose — all from core,
// the polygons as prisms much thicker than they are wide (so every answer lies in the plane z = 0).
#pragma once

#include <vector>

#include "core/cast/conservative_advancement.h"
#include "core/base/types.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

struct ResolutionInput {
    std::vector<Vec2> a;      // world, counter-clockwise (the hull of the scene's points)
    std::vector<Vec2> b;      // B's body frame: its centre (the turning point) is the origin
    Transform start;          // B at t = 0 (rotation about z)
    RigidMotion motion;       // over t in [0, 1] (angular about z)
    double tolerance = 1e-6;  // conservative advancement's touching distance
};

struct ResolutionRun {
    Transform end;  // B at t = 1
    // 1. Minimum translational distance: EPA on the end pose; B moved by depth · n touches A.
    bool penetrating = false;
    double depth = 0.0;
    Vec3 normal = Vec3::Zero();  // from A toward B
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero();
    Transform mtd;
    // 2. Backtracking: B turned as at t = 1, moved back along the linear motion to the first contact.
    bool backtrackHit = false, backtrackAtStart = false;
    double backtrackT = 0.0;
    Vec3 backtrackNormal = Vec3::Zero(), backtrackPoint = Vec3::Zero();
    Transform backtrack;
    // 3. Conservative advancement along the true motion (turning included).
    AdvancementResult advance;
    AdvancementTrace advanceTrace;
    Transform advanced;
};

ResolutionRun runResolution(const ResolutionInput& input);
Json resolutionJson(const ResolutionRun& run);

/// The prism of a polygon (z from −halfThickness to halfThickness), and B's world outline at a pose (z = 0).
std::vector<Vec3> prismOf(const std::vector<Vec2>& polygon, double halfThickness);
std::vector<Vec3> outlineAt(const std::vector<Vec2>& body, const Transform& pose);
/// The turn of a pose about z, degrees.
double angleDegrees(const Transform& pose);

}  // namespace cdlab::demos
