// How the demos choose a view around what a frame shows (demos/draw/figure_style.h viewTowards,
// pair_figure.h acrossGapCamera): checked with the legibility check's own measures on the
// recorded layout (render/legibility.h), not by trusting the chosen direction.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>

#include "core/geometry/polyhedron_presets.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/feature_walk_figure.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/pair_figure.h"
#include "demos/primitives/primitive_figures.h"
#include "render/legibility.h"
#include "tests/gl_test_context.h"

using namespace cdlab;
using namespace cdlab::demos;
using namespace cdlab::render;

namespace {

GlContext& viewContext() { return cdlab::test::glContext(); }

int problemsOf(const FigureLayout& layout, int w, int h, LegibilityKind kind) {
    int n = 0;
    for (const LegibilityProblem& p : checkLegibility(layout, w, h)) n += p.kind == kind;
    return n;
}

}  // namespace

TEST_SUITE("demos") {
    TEST_CASE("viewTowards keeps a view that sees the face, else turns just far enough") {
        const Vec3 view(1.0, 0.8, 1.7);
        CHECK((viewTowards(view, Vec3(0, 0, 1)) - view).norm() == 0);  // 0.82 > 0.5: unchanged
        const Vec3 below(0, -1, 0);  // a face turned away from a view from above
        const Vec3 turned = viewTowards(view, below, 0.5);
        CHECK(turned.normalized().dot(below) >= 0.5);
        CHECK(std::abs(turned.normalized().y()) <= 0.95 + 1e-12);  // never straight down (up is +y)
        CHECK(turned.norm() == doctest::Approx(view.norm()));
        // The least turn: one more step back towards the scene's view would not see it.
        CHECK(turned.normalized().dot(below) < 0.5 + 0.1);
    }

    TEST_CASE("chooseWalkView turns the least that shows a walk's new feature from the front, the bodies apart") {
        using namespace cdlab::demos::walkfigure;
        Body a, b;
        const VClipBuild built = buildVClipPolyhedron(presets::box(Vec3(1, 1, 1)));
        REQUIRE(built.ok());
        a.regions = b.regions = built.polyhedron;
        b.pose.position = Vec3(0, 2.6, 0);  // B above A, 0.6 apart
        const WalkBodies w{&a, a.pose, &b, b.pose, true};
        int plusX = -1;
        for (int f = 0; f < a.regions.mesh().faceCount(); ++f)
            if (a.regions.mesh().plane(f).normal.x() > 0.99) plusX = f;
        REQUIRE(plusX >= 0);
        // The pair: both +x faces; A's +x face is also the new feature (a view that shows one shows all).
        const WalkStepFeatures step{VClipFeature::face(plusX), VClipFeature::face(plusX), 0, VClipFeature::face(plusX)};
        // From the -x side the face is turned away: the view swings round to it...
        const Vec3 v0 = Vec3(-1, 0.3, 1).normalized();
        const Vec3 v = chooseWalkView(w, v0, {step}, 180.0).normalized();
        CHECK(v.x() >= 0.45);  // A's +x face within 63 degrees of the view
        // ... no further than it must: 45 degrees short of the nearest such view would not see it.
        CHECK(std::acos(v.dot(v0)) * 180 / M_PI < 125);
        // ... and B stays apart from A on the picture.
        const CanvasOptions options{640, 480, 1, 1, 1, true};
        Canvas c(viewContext(), options, framingCamera(Vec3(0, 1.3, 0), 3.0, v, Vec3::UnitY(), true));
        c.noteBody("A", worldVertices(a, a.pose), "B");
        c.noteBody("B", worldVertices(b, b.pose), "A");
        CHECK(problemsOf(c.layout(), 640, 480, LegibilityKind::SeparatedBodiesOverlap) == 0);
        // A view that already shows the face is kept, bit for bit, and so is one step's scene view.
        const Vec3 good = Vec3(1, 0.05, 0.6);  // level with the gap: apart
        CHECK((chooseWalkView(w, good, {step}, 180.0) - good).norm() == 0);
        CHECK((stepView(w, good, step) - good).norm() == 0);
        CHECK(stepView(w, v0, step).normalized().x() >= 0.45);
    }

    TEST_CASE("viewAcross lies across its line and looks down where a view across it can") {
        // primitives/sphere_obb's centre line: the preferred view turned across it looked from below.
        const Vec3 line(-0.35, -0.6, -0.61), preferred(1.0, 0.8, 1.7);
        const Vec3 v = viewAcross(preferred, line);
        CHECK(std::abs(v.normalized().dot(line.normalized())) < 1e-12);
        CHECK(v.normalized().y() >= 0.3);
        // A view across that already looks down is kept as the plain projection.
        const Vec3 flat(1, 0, 0);
        CHECK((viewAcross(preferred, flat) - Vec3(0, 0.8, 1.7)).norm() < 1e-15);
        // A vertical line: every view across it is level; a level one it is.
        CHECK(std::abs(viewAcross(preferred, Vec3(0, 1, 0)).y()) < 1e-12);
    }

    TEST_CASE("acrossGapCamera: a separated pair overlapping on the picture is seen across its gap") {
        // Two unit boxes 0.01 apart along y, seen from above at an angle: their pictures overlap.
        PairDrawing d;
        d.a = boxDrawable(Obb{Vec3(0, 0, 0), Vec3(1, 1, 1), Eigen::Matrix3d::Identity()});
        d.b = boxDrawable(Obb{Vec3(0.3, 2.01, 0.2), Vec3(1, 1, 1), Eigen::Matrix3d::Identity()});
        const CanvasOptions options{640, 480, 1, 1, 1, true};
        const Camera base = framingCamera(Vec3(0.15, 1.0, 0.1), 2.5, Vec3(1.0, 0.8, 1.7), Vec3::UnitY(), true);
        const auto picture = [&](const Camera& cam) {
            Canvas c(viewContext(), options, cam);
            c.noteBody("A", d.a.vertices, "B");
            c.noteBody("B", d.b.vertices, "A");
            return c.layout();
        };
        REQUIRE(problemsOf(picture(base), 640, 480, LegibilityKind::SeparatedBodiesOverlap) == 2);
        const Camera across =
            acrossGapCamera(viewContext(), options, base, d, Vec3(0.3, 1.0, 0.2), Vec3(0.3, 1.01, 0.2));
        CHECK(problemsOf(picture(across), 640, 480, LegibilityKind::SeparatedBodiesOverlap) == 0);
        CHECK(std::abs((across.eye - Vec3(0.3, 1.005, 0.2)).y()) < 1e-9);  // the eye in the midway plane
        CHECK((across.eye - across.target).norm() == doctest::Approx((base.eye - base.target).norm()));
        // Already apart on the picture (a view from the side): the scene's camera is kept.
        const Camera side = framingCamera(Vec3(0.15, 1.0, 0.1), 2.5, Vec3(1.0, 0.0, 0.3), Vec3::UnitY(), true);
        const Camera kept = acrossGapCamera(viewContext(), options, side, d, Vec3(0.3, 1.0, 0.2), Vec3(0.3, 1.01, 0.2));
        CHECK((kept.eye - side.eye).norm() == 0);
    }
}
