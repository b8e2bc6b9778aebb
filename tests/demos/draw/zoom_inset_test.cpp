// The zoomed inset of a quantity drawn too short (demos/draw/zoom_inset.h): what the review rule
// QuantityTooSmall (render/legibility.h) accepts, measured on the recorded layout, not trusted.
#include <doctest/doctest.h>

#include <memory>

#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/zoom_inset.h"
#include "render/legibility.h"
#include "tests/gl_test_context.h"

using namespace cdlab;
using namespace cdlab::demos;
using namespace cdlab::render;

namespace {

GlContext& context() { return cdlab::test::glContext(); }

// Two 2 x 1 rectangles `gap` apart in a 2D view 20 units high on an 800 x 600 canvas (30 px per
// unit), and the quantity between them.
struct TwoSquares {
    double gap;
    void draw(Canvas& c) const {
        const auto square = [&](double x0) {
            c.drawPolyline({Vec3(x0, -0.5, 0), Vec3(x0 + 2, -0.5, 0), Vec3(x0 + 2, 0.5, 0), Vec3(x0, 0.5, 0)}, true,
                           lineStyle(Role::Ink, 2.0f, false, true));
        };
        square(-2.0);
        square(gap);
    }
    ZoomTarget target() const {
        return {"gap", "gap", Vec3(0, 0, 0), Vec3(gap, 0, 0), [this](Canvas& c) { draw(c); }};
    }
};

double longest(const FigureLayout& layout, const std::string& name) {
    double px = 0;
    for (const LayoutQuantity& q : layout.quantities)
        if (q.name == name) px = std::max(px, q.px);
    return px;
}

}  // namespace

TEST_CASE("a quantity drawn too short gets a zoomed inset") {
    const TwoSquares scene{0.2};  // 6 px on the picture
    Canvas c(context(), canvasOptions(800, 600, 1), Camera::twoD(0, 0, 20));
    scene.draw(c);
    c.noteQuantity("gap", Vec3(0, 0, 0), Vec3(scene.gap, 0, 0));
    const Image plain = c.readPixels();
    CHECK(longest(plain.layout, "gap") == doctest::Approx(6.0).epsilon(0.02));
    const Image zoomed = readPixelsZoomed(context(), c, 1, scene.target(), Box{10, 10, 790, 590});
    // The largest inset, 9/20 of 780 x 580, hides nothing: it draws the gap at a sixth of its
    // picture's height, (261 - heading) / 6 px.
    CHECK(longest(zoomed.layout, "gap") == doctest::Approx((261 - kZoomHeadingPx) / 6.0).epsilon(0.02));
    bool quantityProblem = false;
    for (const LegibilityProblem& p : checkLegibility(zoomed.layout, zoomed.width, zoomed.height))
        quantityProblem |= p.kind == LegibilityKind::QuantityTooSmall;
    CHECK_FALSE(quantityProblem);
    // The heading names the zoom: the inset's 233 px per 1.2 units against the picture's 30 px per unit.
    bool headed = false;
    for (const LayoutLabel& l : zoomed.layout.labels) headed |= l.text.rfind("zoom ×6.5: gap", 0) == 0;
    CHECK(headed);
    // The inset sits in a corner that holds neither rectangle (the bottom right, the first tried):
    // its ink border, 2 px inside its box (439..790 x 329..590), where the plain picture is blank.
    for (const auto& [x, y] : {std::pair{600, 589}, std::pair{440, 450}, std::pair{789, 450}, std::pair{600, 330}}) {
        CHECK(zoomed.pixel(x, y)[0] < 80);
        CHECK(plain.pixel(x, y)[0] > 200);
    }
}

TEST_CASE("a quantity drawn long enough is read as it is, with no inset") {
    const TwoSquares scene{1.0};  // 30 px
    Canvas c(context(), canvasOptions(800, 600, 1), Camera::twoD(0, 0, 20));
    scene.draw(c);
    const Image plain = c.readPixels();
    const Image same = readPixelsZoomed(context(), c, 1, scene.target(), Box{10, 10, 790, 590});
    CHECK(pixelHash(same) == pixelHash(plain));
    CHECK(same.layout.labels.size() == plain.layout.labels.size());
}
