// The renderer end to end on whatever EGL gives (llvmpipe here): known pixels, ordering,
// translucency, MSAA clamping, supersampling, text, determinism. One GlContext per executable:
// creating one is slow on llvmpipe.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "render/canvas.h"
#include "render/compare.h"
#include "render/legibility.h"
#include "tests/gl_test_context.h"

using namespace cdlab::render;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::Vector3i;

namespace {

GlContext& context() { return cdlab::test::glContext(); }

/// Colour as the framebuffer stores it (unorm8 rounding).
int u8(float c) { return int(std::lround(c * 255.0f)); }

/// Max channel difference (RGB) between a pixel and a colour.
int delta(const Image& im, int x, int y, const Color& c) {
    const std::uint8_t* p = im.pixel(x, y);
    return std::max({std::abs(p[0] - u8(c.r)), std::abs(p[1] - u8(c.g)), std::abs(p[2] - u8(c.b))});
}

const Color kWhite{1, 1, 1, 1};

/// 200x200 px, 2D camera showing [-5, 5]^2: 20 px per unit, world (0,0) at pixel corner (100,100).
void scene2d(Canvas& c) {
    c.setCamera(Camera::twoD(0, 0, 10));
    c.setBackground(kWhite);
    // Upper-left square: tells y-up from y-down.
    c.drawPolygon({{-4, 1, 0}, {-1, 1, 0}, {-1, 4, 0}, {-4, 4, 0}}, roleColor(Role::ShapeA));
    // Horizontal 8 px line at y = -3: pixel rows 156..163 fully covered.
    c.drawLine({-4, -3, 0}, {4, -3, 0}, {8, roleColor(Role::Ink)});
    // Dashed 4 px line at y = 0.5 (row 90), x from px 110 to 190, dashes of 10 px.
    c.drawLine({0.5, 0.5, 0}, {4.5, 0.5, 0}, {4, roleColor(Role::Direction), 10});
    // 20 px point (radius 10) with a 2 px outline, centred on pixel corner (150, 50).
    c.drawPoint({2.5, 2.5, 0}, 10, roleColor(Role::Result), true, 2, roleColor(Role::Ink));
    c.drawArrow({-4, -1, 0}, {-1, -1, 0}, {3, roleColor(Role::Support)});
}

}  // namespace

TEST_SUITE("render/canvas") {
    TEST_CASE("context: OpenGL 3.3+ core on a headless EGL platform") {
        GlContext& ctx = context();
        MESSAGE("GL_RENDERER=" << ctx.glRenderer() << " GL_VERSION=" << ctx.glVersion()
                               << " EGL platform=" << ctx.eglPlatform() << " GL_MAX_SAMPLES=" << ctx.maxSamples());
        CHECK(!ctx.glRenderer().empty());
        const std::string p = ctx.eglPlatform();
        CHECK((p == "device" || p == "surfaceless" || p == "default"));
        CHECK(ctx.maxSamples() >= 1);
    }

    TEST_CASE("2D: known colours at known pixels, y up, first row on top") {
        Canvas c(context(), {200, 200, 1, 4});
        scene2d(c);
        const Image im = c.readPixels();
        REQUIRE(im.width == 200);
        REQUIRE(im.height == 200);
        CHECK(delta(im, 2, 2, kWhite) == 0);                     // background
        CHECK(delta(im, 50, 50, roleColor(Role::ShapeA)) <= 1);  // square, upper left
        CHECK(delta(im, 50, 150, kWhite) == 0);                  // nothing lower left
        CHECK(delta(im, 21, 21, roleColor(Role::ShapeA)) <= 1);  // just inside the corner (-3.95, 3.95)
        CHECK(delta(im, 19, 19, kWhite) == 0);                   // just outside
        CHECK(delta(im, 100, 156, roleColor(Role::Ink)) <= 1);   // thick line, top row
        CHECK(delta(im, 100, 163, roleColor(Role::Ink)) <= 1);   // bottom row
        CHECK(delta(im, 100, 166, kWhite) == 0);                 // 6.5 px from the axis
        CHECK(delta(im, 100, 153, kWhite) == 0);
        CHECK(delta(im, 100, 164, kWhite) == 0);  // exactly 8 rows: 156..163
        CHECK(delta(im, 100, 155, kWhite) == 0);
        CHECK(delta(im, 150, 50, roleColor(Role::Result)) <= 1);  // point centre: fill
        CHECK(delta(im, 158, 50, roleColor(Role::Ink)) <= 1);     // 8.5 px: the outline ring
        CHECK(delta(im, 150, 41, roleColor(Role::Ink)) <= 1);     // ring above the centre
        const int rim = delta(im, 159, 50, kWhite);               // 9.5 px: the ring, AA edge near
        CHECK(rim > 150);
        CHECK(delta(im, 163, 50, kWhite) == 0);                      // outside the disc
        CHECK(delta(im, 115, 90, roleColor(Role::Direction)) <= 1);  // inside the first dash
        CHECK(delta(im, 125, 90, kWhite) == 0);                      // in the first gap
        CHECK(delta(im, 135, 90, roleColor(Role::Direction)) <= 1);  // second dash
        CHECK(delta(im, 40, 120, roleColor(Role::Support)) <= 1);    // arrow shaft at y = -1
        CHECK(delta(im, 72, 120, roleColor(Role::Support)) <= 1);    // head, 8 px before the tip (x = 80)
        CHECK(delta(im, 72, 124, kWhite) == 0);                      // the head is narrow there
        CHECK(delta(im, 66, 116, roleColor(Role::Support)) <= 1);    // wider further back
        CHECK(delta(im, 84, 120, kWhite) == 0);                      // nothing past the tip
    }

    TEST_CASE("the same commands give the same pixels, in one canvas and in a new one") {
        Canvas a(context(), {200, 200, 1, 4});
        scene2d(a);
        a.drawTextPx(100, 10, "λ ≤ α · 2 → ∞", {16, roleColor(Role::Ink), Anchor::Top});
        const Image first = a.readPixels();
        const Image second = a.readPixels();
        CHECK(pixelHash(first) == pixelHash(second));
        Canvas b(context(), {200, 200, 1, 4});
        scene2d(b);
        b.drawTextPx(100, 10, "λ ≤ α · 2 → ∞", {16, roleColor(Role::Ink), Anchor::Top});
        CHECK(pixelHash(b.readPixels()) == pixelHash(first));
        a.clearCommands();
        const Image empty = a.readPixels();
        CHECK(pixelHash(empty) != pixelHash(first));
        CHECK(delta(empty, 150, 50, roleColor(Role::Background)) == 0);
    }

    TEST_CASE("the harness can fail: perturbed and shifted renders are rejected at the default tolerance") {
        Canvas c(context(), {200, 200, 1, 4});
        scene2d(c);
        const Image golden = c.readPixels();
        Image few = golden;
        for (int k = 0; k < 3; ++k) few.pixel(30 + 40 * k, 70)[1] ^= 4;
        CHECK_FALSE(compareImages(few, golden).passed);
        Image shifted = golden;  // one pixel to the right
        for (int y = 0; y < 200; ++y)
            for (int x = 199; x > 0; --x) std::copy_n(golden.pixel(x - 1, y), 4, shifted.pixel(x, y));
        const CompareResult r = compareImages(shifted, golden);
        CHECK_FALSE(r.passed);
        CHECK(r.maxDelta > 100);
        // The same scene moved by one camera pixel is rejected too.
        Canvas moved(context(), {200, 200, 1, 4});
        scene2d(moved);
        moved.setCamera(Camera::twoD(-0.05, 0, 10));
        CHECK_FALSE(compareImages(moved.readPixels(), golden).passed);
    }

    TEST_CASE("3D: opaque faces hide depth-tested lines, onTop lines and points stay visible") {
        Canvas c(context(), {200, 200, 1, 4});
        Camera cam;
        cam.eye = {0, 0, 5};
        cam.target = {0, 0, 0};
        c.setCamera(cam);
        c.setBackground(kWhite);
        const Color red{0.8f, 0.1f, 0.1f, 1};
        c.drawPolygon({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, red);  // unlit: exact colour
        const LineStyle hidden{6, roleColor(Role::Ink)};
        LineStyle onTop{6, roleColor(Role::Direction)};
        onTop.onTop = true;
        c.drawLine({-0.8, 0.5, -1}, {0.8, 0.5, -1}, hidden);  // behind the square
        c.drawLine({-0.8, -0.5, -1}, {0.8, -0.5, -1}, onTop);
        c.drawLine({-0.8, 0, 0.5}, {0.8, 0, 0.5}, hidden);                   // in front of it
        c.drawPoint({0.5, 0.25, -1}, 6, roleColor(Role::Result), false, 0);  // hidden
        c.drawPoint({-0.5, 0.25, -1}, 6, roleColor(Role::Result), true, 0);  // on top
        const Image im = c.readPixels();
        Vector2d px;
        auto at = [&](const Vector3d& p) {
            REQUIRE(c.project(p, px));
            return std::make_pair(int(px.x()), int(px.y()));
        };
        auto [x1, y1] = at({0, 0.5, -1});
        CHECK(delta(im, x1, y1, red) <= 1);
        auto [x2, y2] = at({0, -0.5, -1});
        CHECK(delta(im, x2, y2, roleColor(Role::Direction)) <= 1);
        auto [x3, y3] = at({0, 0, 0.5});
        CHECK(delta(im, x3, y3, roleColor(Role::Ink)) <= 1);
        auto [x4, y4] = at({0.5, 0.25, -1});
        CHECK(delta(im, x4, y4, red) <= 1);
        auto [x5, y5] = at({-0.5, 0.25, -1});
        CHECK(delta(im, x5, y5, roleColor(Role::Result)) <= 1);
        CHECK(delta(im, 3, 3, kWhite) == 0);
    }

    TEST_CASE("translucent faces blend back to front whatever the call order") {
        const Color green{0.0f, 0.6f, 0.3f, 0.5f}, blue{0.0f, 0.3f, 0.9f, 0.5f};
        const std::vector<Vector3d> nearQuad = {{-1, -1, 0.5}, {0.5, -1, 0.5}, {0.5, 0.5, 0.5}, {-1, 0.5, 0.5}};
        const std::vector<Vector3d> farQuad = {{-0.5, -0.5, 0}, {1, -0.5, 0}, {1, 1, 0}, {-0.5, 1, 0}};
        Camera cam;
        cam.eye = {0, 0, 6};
        Image images[2];
        for (int order = 0; order < 2; ++order) {
            Canvas c(context(), {160, 160, 1, 4});
            c.setCamera(cam);
            c.setBackground(kWhite);
            if (order == 0) {
                c.drawPolygon(nearQuad, green);
                c.drawPolygon(farQuad, blue);
            } else {
                c.drawPolygon(farQuad, blue);
                c.drawPolygon(nearQuad, green);
            }
            images[order] = c.readPixels();
            Vector2d px;
            REQUIRE(c.project({0, 0, 0.25}, px));  // inside both
            // Over white: far first, then near: near.a * near + (1 - near.a) * (far.a * far + (1 - far.a) * white).
            auto blend = [&](float n, float f, float w) { return 0.5f * n + 0.5f * (0.5f * f + 0.5f * w); };
            const Color expected{blend(green.r, blue.r, 1), blend(green.g, blue.g, 1), blend(green.b, blue.b, 1), 1};
            CHECK(delta(images[order], int(px.x()), int(px.y()), expected) <= 2);
        }
        CHECK(pixelHash(images[0]) == pixelHash(images[1]));
    }

    TEST_CASE("MSAA: 8 samples requested is clamped to what the driver supports and still renders") {
        Canvas eight(context(), {200, 200, 1, 8});
        scene2d(eight);
        const Image im = eight.readPixels();
        CHECK(eight.samples() >= 1);
        CHECK(eight.samples() <= std::min(8, context().maxSamples()));
        CHECK(delta(im, 50, 50, roleColor(Role::ShapeA)) <= 1);
        CHECK(delta(im, 150, 50, roleColor(Role::Result)) <= 1);
        Canvas none(context(), {200, 200, 1, 0});  // 0 or 1: no multisampling
        scene2d(none);
        CHECK(delta(none.readPixels(), 100, 158, roleColor(Role::Ink)) <= 1);
        CHECK(none.samples() == 1);
        if (context().maxSamples() == 4) {
            Canvas four(context(), {200, 200, 1, 4});
            scene2d(four);
            CHECK(pixelHash(four.readPixels()) == pixelHash(im));
        }
    }

    TEST_CASE("supersampling: same output size, same interiors, smoother edges") {
        Canvas s1(context(), {200, 200, 1, 4});
        Canvas s2(context(), {200, 200, 2, 4});
        scene2d(s1);
        scene2d(s2);
        const Image a = s1.readPixels(), b = s2.readPixels();
        REQUIRE(b.width == 200);
        REQUIRE(b.height == 200);
        CHECK(delta(b, 50, 50, roleColor(Role::ShapeA)) <= 1);
        CHECK(delta(b, 100, 158, roleColor(Role::Ink)) <= 1);
        CHECK(delta(b, 150, 50, roleColor(Role::Result)) <= 1);
        CHECK(pixelHash(a) != pixelHash(b));
        CHECK(compareImages(b, a, {64, 0, 0.01}).passed);  // same picture, edges differ a little
    }

    TEST_CASE("scale: a print figure is the same picture at twice the pixels, its layout twice as large") {
        CanvasOptions o1{200, 200, 1, 4}, o2{200, 200, 1, 4};
        o2.scale = 2;
        Canvas s1(context(), o1), s2(context(), o2);
        for (Canvas* c : {&s1, &s2}) {
            scene2d(*c);
            c->drawTextPx(20, 120, "label", TextStyle{18, roleColor(Role::Ink), Anchor::TopLeft, false, false});
        }
        CHECK(s2.width() == 200);  // the drawing API stays in scale-1 units
        const Image a = s1.readPixels(), b = s2.readPixels();
        REQUIRE(b.width == 400);
        REQUIRE(b.height == 400);
        CHECK(b.scale == 2);
        // The same colours at the same places (pixel (x, y) of a is pixel (2x, 2y) of b).
        CHECK(delta(b, 100, 100, roleColor(Role::ShapeA)) <= 1);
        CHECK(delta(b, 200, 316, roleColor(Role::Ink)) <= 1);
        CHECK(delta(b, 300, 100, roleColor(Role::Result)) <= 1);
        CHECK(compareImages(downsample(b, 2), a, {64, 0, 0.02}).passed);
        REQUIRE(a.layout.labels.size() == b.layout.labels.size());
        REQUIRE(!a.layout.labels.empty());
        for (std::size_t i = 0; i < a.layout.labels.size(); ++i)
            CHECK(b.layout.labels[i].box.x1 == doctest::Approx(2 * a.layout.labels[i].box.x1));
    }

    TEST_CASE("text: ink inside the measured box, none outside it") {
        Canvas c(context(), {320, 120, 1, 4});
        c.setCamera(Camera::twoD(0, 0, 10));
        c.setBackground(kWhite);
        TextStyle style{24, roleColor(Role::Ink), Anchor::TopLeft, false, false};
        const std::string text = "Hello λα · x ≤ 1 → y";
        const Vector2d box = c.measureText(text, style);
        CHECK(box.x() > 150);
        CHECK(box.y() == doctest::Approx(24));
        TextStyle bold = style;
        bold.bold = true;
        CHECK(c.measureText(text, bold).x() > box.x());
        const int x0 = 20, y0 = 30;
        c.drawTextPx(x0, y0, text, style);
        const Image im = c.readPixels();
        int inside = 0, outside = 0;
        for (int y = 0; y < im.height; ++y)
            for (int x = 0; x < im.width; ++x) {
                if (delta(im, x, y, kWhite) == 0) continue;
                const bool in = x >= x0 - 2 && x <= x0 + box.x() + 2 && y >= y0 - 2 && y <= y0 + box.y() + 2;
                (in ? inside : outside)++;
            }
        CHECK(inside > 300);
        CHECK(outside == 0);
        // Centre anchor: the box is centred on the point.
        Canvas d(context(), {320, 120, 1, 4});
        d.setBackground(kWhite);
        d.drawTextPx(160, 60, "MMMM", {30, roleColor(Role::Ink), Anchor::Center, false, false});
        const Image cm = d.readPixels();
        int minX = 1000, maxX = -1;
        for (int y = 0; y < cm.height; ++y)
            for (int x = 0; x < cm.width; ++x)
                if (delta(cm, x, y, kWhite) > 0) minX = std::min(minX, x), maxX = std::max(maxX, x);
        CHECK(std::abs((minX + maxX) / 2.0 - 160) <= 3);
    }

    TEST_CASE("degenerate input draws what it can and never crashes") {
        Canvas c(context(), {100, 100, 1, 4});
        const double nan = std::numeric_limits<double>::quiet_NaN();
        c.drawMesh({{0, 0, 0}, {nan, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}, roleColor(Role::ShapeA));
        c.drawMesh({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, {{0, 1, 2}}, roleColor(Role::ShapeA));  // zero area
        c.drawLine({0, 0, 0}, {0, 0, 0}, {4, roleColor(Role::Ink)});                          // zero length: a dot
        c.drawLine({0, 0, 0}, {nan, 0, 0}, {4, roleColor(Role::Ink)});
        c.drawLine({0, 0, 0}, {0, 0, 100}, {4, roleColor(Role::Ink)});  // through the eye plane
        c.drawArrow({1, 1, 1}, {1, 1, 1}, {4, roleColor(Role::Ink)});
        c.drawPolyline({}, true, {});
        c.drawPolygon({{0, 0, 0}, {1, 0, 0}}, roleColor(Role::ShapeA));
        c.drawPoint({0, 0, 10}, 5, roleColor(Role::Ink));  // behind the eye
        c.drawPoint({0, 0, 0}, 0, roleColor(Role::Ink));
        c.drawText({0, 0, 10}, "behind", {});
        c.drawTextPx(10, 10, "", {});
        c.drawTextPx(10, 10, "\xff\xfe bad \xe2\x82 utf8 \xf0\x9f\x98\x80", {});
        c.drawTextPx(nan, 10, "nan", {});
        CHECK_THROWS_AS(c.drawMesh({{0, 0, 0}}, {{0, 1, 2}}, roleColor(Role::ShapeA)), std::out_of_range);
        const Image im = c.readPixels();
        CHECK(im.width == 100);
        CHECK_THROWS_AS(Canvas(context(), {0, 10, 1, 4}), std::invalid_argument);
    }

    TEST_CASE("sample figures and frame times (written when CDLAB_SAMPLE_DIR is set)") {
        const char* dir = std::getenv("CDLAB_SAMPLE_DIR");
        if (!dir) return;
        const double t = (1 + std::sqrt(5.0)) / 2;
        std::vector<Vector3d> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
        for (auto& p : v) p.normalize();
        const std::vector<Vector3i> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
        auto figure3d = [&](Canvas& c) {
            Camera cam;
            cam.eye = {3.2, 2.4, 4.5};
            c.setCamera(cam);
            std::vector<Vector3d> other;
            for (auto& p : v) other.push_back(p * 0.5 + Vector3d(1.4, -0.3, -0.6));
            c.drawMesh(other, f, roleColor(Role::ShapeB));
            c.drawMesh(v, f, roleColor(Role::ShapeA).withAlpha(0.45f));
            c.drawPolygon({{-2, -1.2, -2}, {2, -1.2, -2}, {2, -1.2, 2}, {-2, -1.2, 2}},
                          roleColor(Role::Muted).withAlpha(0.25f));
            for (auto& tri : f)
                for (int k = 0; k < 3; ++k) c.drawLine(v[tri[k]], v[tri[(k + 1) % 3]], {1.5f, roleColor(Role::Ink)});
            c.drawLine({-2, 0, 0}, {2, 0, 0}, {2, roleColor(Role::Muted), 8});
            c.drawLine({0, -1.5, 0}, {0, 1.8, 0}, {3, roleColor(Role::Highlight), 10, true});
            c.drawArrow({0, 0, 0}, {1.5, 1.2, 0.8}, {3, roleColor(Role::Direction)});
            c.drawArrow({0, 0, 0}, {-0.9, 0.9, 1.2}, {2, roleColor(Role::Support), 6, true});
            c.drawPoint({0, 0, 0}, 7, roleColor(Role::Origin), true, 0);
            c.drawPoint(v[5], 9, roleColor(Role::Result), true, 2, roleColor(Role::Ink));
            c.drawText({1.5, 1.2, 0.8}, "direction d", {20, roleColor(Role::Direction), Anchor::BottomLeft});
            c.drawText(v[5], "witness  λ = 0.42", {18, roleColor(Role::Ink), Anchor::Left});
            c.drawText({0, 0, 0}, "O", {22, roleColor(Role::Ink), Anchor::TopRight, true, true});
            c.drawTextPx(512, 16, "Translucent icosahedron · perspective",
                         {26, roleColor(Role::Ink), Anchor::Top, true, true});
        };
        for (int scale : {1, 2}) {
            Canvas c(context(), {1024, 1024, scale, 4});
            figure3d(c);
            c.readPixels();  // warm-up: glyph atlases, render target
            const auto start = std::chrono::steady_clock::now();
            constexpr int kFrames = 5;
            Image im;
            for (int i = 0; i < kFrames; ++i) im = c.readPixels();
            const double ms =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / kFrames;
            MESSAGE("1024x1024 scale " << scale << ": " << ms << " ms per frame (render + readback)");
            writePngAtomic(std::string(dir) + "/sample_3d_s" + std::to_string(scale) + ".png", im);
        }
        Canvas c2(context(), {800, 600, 1, 4});
        c2.setCamera(Camera::twoD(0, 0, 6));
        c2.drawPolygon({{-2.5, -1.5, 0}, {0.5, -2, 0}, {1, 1, 0}, {-1.5, 1.8, 0}},
                       roleColor(Role::Minkowski).withAlpha(0.5f));
        c2.drawPolyline({{-2.5, -1.5, 0}, {0.5, -2, 0}, {1, 1, 0}, {-1.5, 1.8, 0}}, true, {2.5f, roleColor(Role::Ink)});
        c2.drawLine({-3.8, 0, 0}, {3.8, 0, 0}, {1, roleColor(Role::Muted)});
        c2.drawLine({0, -2.8, 0}, {0, 2.8, 0}, {1, roleColor(Role::Muted)});
        c2.drawArrow({0, 0, 0}, {2.5, 2, 0}, {3, roleColor(Role::Direction)});
        c2.drawLine({-3, 2.5, 0}, {3, -2.5, 0}, {2, roleColor(Role::Highlight), 9});
        c2.drawPoint({0, 0, 0}, 6, roleColor(Role::Origin), true, 0);
        c2.drawPoint({1, 1, 0}, 10, roleColor(Role::Support), true, 2, roleColor(Role::Ink));
        c2.drawText({2.5, 2, 0}, "d (y up)", {20, roleColor(Role::Direction), Anchor::BottomLeft});
        c2.drawText({1, 1, 0}, "support s = (1, 1)", {18, roleColor(Role::Ink), Anchor::Left});
        c2.drawTextPx(10, 10, "2D · first row on top", {22, roleColor(Role::Ink), Anchor::TopLeft, true, true});
        writePngAtomic(std::string(dir) + "/sample_2d.png", c2.readPixels());
    }
}

TEST_SUITE("canvas layout") {
    TEST_CASE("readPixels records every stroke in pixels with its width, and a placed label's leader as its own") {
        Canvas c(context(), CanvasOptions{200, 200, 1, 4});
        c.setCamera(Camera::twoD(0, 0, 10));
        c.drawLine(Vector3d(-4, 1, 0), Vector3d(4, 1, 0), LineStyle{2.0f, Color{0, 0, 0, 1}});
        c.drawPolyline({Vector3d(-3, -3, 0), Vector3d(3, -3, 0), Vector3d(3, 3, 0)}, false,
                       LineStyle{1.0f, Color{0, 0, 0, 1}});
        c.drawArrow(Vector3d(0, 0, 0), Vector3d(2, 2, 0), LineStyle{3.0f, Color{0, 0, 0, 1}});
        c.drawPoint(Vector3d(0, -1, 0), 40.0f, Color{0, 0, 0, 1});  // a disc over the first ring
        TextStyle placed{16.0f, Color{0, 0, 0, 1}};
        placed.offsetPx = Vector2d(0, 40);  // the second ring: placed with a leader line
        placed.place = true;
        c.drawText(Vector3d(0, -1, 0), "p", placed);
        const Image im = c.readPixels();
        const FigureLayout& l = im.layout;
        Vector2d a, b;
        REQUIRE(c.project(Vector3d(-4, 1, 0), a));
        REQUIRE(c.project(Vector3d(4, 1, 0), b));
        REQUIRE(l.strokes.size() >= 4);  // the line, two polyline segments, the arrow (+ a leader)
        CHECK((l.strokes[0].a - a).norm() < 1e-9);
        CHECK((l.strokes[0].b - b).norm() < 1e-9);
        CHECK(l.strokes[0].width == 2.0);
        CHECK(l.strokes[1].width == 1.0);
        CHECK(l.strokes[3].width == 3.0);
        int leaders = 0;
        for (const LayoutStroke& k : l.strokes)
            if (k.leaderOf >= 0) {
                ++leaders;
                REQUIRE(k.leaderOf < int(l.labels.size()));
                CHECK(l.labels[std::size_t(k.leaderOf)].text == "p");
            }
        CHECK(leaders == 1);
    }

    TEST_CASE("strokes drawn under a stroke owner outline the body its name label names") {
        Canvas c(context(), CanvasOptions{200, 200, 1, 4});
        c.setCamera(Camera::twoD(0, 0, 10));
        LineStyle s;
        s.widthPx = 1.5f;
        c.setStrokeOwner(7);
        c.drawPolyline({Vector3d(-3, -3, 0), Vector3d(3, -3, 0), Vector3d(3, 3, 0)}, true, s);
        c.setStrokeOwner(0);
        c.drawLine(Vector3d(-4, 0, 0), Vector3d(4, 0, 0), s);
        TextStyle name;
        name.names = 7;
        c.drawText(Vector3d(1, 1, 0), "B", name);
        const FigureLayout l = c.readPixels().layout;
        REQUIRE(l.labels.size() == 1);
        REQUIRE(l.strokes.size() == 4);
        for (int k = 0; k < 3; ++k) CHECK(l.strokes[std::size_t(k)].outlineOf == 0);
        CHECK(l.strokes[3].outlineOf == -1);
    }

    TEST_CASE("a label naming any of several points goes to the one with a clean spot, the first on a tie") {
        // 400 x 300 px, one world unit a pixel, y up. The first point sits in a mesh of lines 8 px
        // apart (no spot near it is clean, a leader out crosses lines); the second in open space.
        const auto drawMesh = [](Canvas& c) {
            LineStyle s;
            s.widthPx = 1.0f;
            for (double k = 0; k <= 240; k += 8) {
                c.drawLine(Vector3d(0, 30 + k, 0), Vector3d(240, 30 + k, 0), s);
                c.drawLine(Vector3d(k, 30, 0), Vector3d(k, 270, 0), s);
            }
        };
        TextStyle ts;
        ts.sizePx = 16.0f;
        ts.place = true;
        ts.offsetPx = Vector2d(0, -16);
        {
            Canvas c(context(), CanvasOptions{400, 300, 1, 4}, Camera::pixels(400, 300));
            drawMesh(c);
            c.drawTextAtAnyOf({Vector3d(124, 150, 0), Vector3d(330, 150, 0)}, "face", ts);
            const FigureLayout laidOut = c.layout();  // the same placement, without drawing
            const FigureLayout l = c.readPixels().layout;
            REQUIRE(l.labels.size() == 1);
            REQUIRE(laidOut.labels.size() == 1);
            CHECK(laidOut.labels[0].box.x0 == l.labels[0].box.x0);
            CHECK(laidOut.labels[0].box.y0 == l.labels[0].box.y0);
            CHECK(laidOut.strokes.size() == l.strokes.size());
            REQUIRE(l.labels[0].anchor);
            CHECK((*l.labels[0].anchor - Vector2d(330, 150)).norm() < 1e-9);
            CHECK(l.labels[0].box.distanceTo(Vector2d(330, 150)) < 20);
            CHECK(checkLegibility(l, 400, 300).empty());
        }
        {
            // Both clean: the first.
            Canvas c(context(), CanvasOptions{400, 300, 1, 4}, Camera::pixels(400, 300));
            c.drawTextAtAnyOf({Vector3d(300, 100, 0), Vector3d(330, 150, 0)}, "face", ts);
            const FigureLayout l = c.readPixels().layout;
            REQUIRE(l.labels.size() == 1);
            CHECK((*l.labels[0].anchor - Vector2d(300, 200)).norm() < 1e-9);
        }
    }

    TEST_CASE("a canvas without text draws the same picture less its texts and lays none out") {
        const auto draw = [&](bool text) {
            CanvasOptions o{200, 200, 1, 4};
            o.text = text;
            Canvas c(context(), o);
            c.setCamera(Camera::twoD(0, 0, 10));
            c.setBackground(kWhite);
            c.drawLine(Vector3d(-4, 0, 0), Vector3d(4, 0, 0), LineStyle{});
            c.drawPoint(Vector3d(0, 0, 0), 6.0f, Color{0, 0, 0, 1});
            TextStyle placed{16.0f, Color{0, 0, 0, 1}};
            placed.offsetPx = Vector2d(40, -40);
            placed.place = true;
            c.drawText(Vector3d(0, 0, 0), "label", placed);
            c.drawTextPx(10, 10, "title", TextStyle{16.0f, Color{0, 0, 0, 1}, Anchor::TopLeft});
            return c.readPixels();
        };
        const Image with = draw(true), without = draw(false);
        CHECK(with.layout.labels.size() == 2);
        CHECK(without.layout.labels.empty());
        CHECK(without.layout.strokes.size() == 1);  // the line, no leader
        CHECK(without.layout.markers.size() == 1);
        int inked = 0;  // dark pixels in the title's corner: none without text
        for (int y = 8; y < 30; ++y)
            for (int x = 8; x < 60; ++x) inked += without.pixel(x, y)[0] < 128;
        CHECK(inked == 0);
        CHECK(pixelHash(with) != pixelHash(without));
    }

    TEST_CASE("readPixels records text boxes, markers and who names them, placed labels go around the rest") {
        Canvas c(context(), CanvasOptions{200, 200, 1, 4});
        c.setCamera(Camera::twoD(0, 0, 10));
        c.setBackground(kWhite);
        c.drawPoint(Vector3d(0, 0, 0), 6.0f, Color{0, 0, 0, 1});
        TextStyle fixed{16.0f, Color{0, 0, 0, 1}, Anchor::Left, false, false};
        fixed.offsetPx = Vector2d(8, 0);
        c.drawText(Vector3d(0, 0, 0), "fixed", fixed);  // right of the point
        TextStyle placed{16.0f, Color{0, 0, 0, 1}};
        placed.offsetPx = Vector2d(20, 0);  // asks for the same side
        placed.place = true;
        c.drawText(Vector3d(0, 0, 0), "moved", placed);
        c.drawTextPx(4, 4, "title", TextStyle{16.0f, Color{0, 0, 0, 1}, Anchor::TopLeft, false, false});
        const Image im = c.readPixels();
        const FigureLayout& l = im.layout;
        REQUIRE(l.panels.size() == 1);
        CHECK(l.panels[0].x1 == 200);
        REQUIRE(l.labels.size() == 3);
        REQUIRE(l.markers.size() == 1);
        CHECK(l.markers[0].box.center().x() == doctest::Approx(100));
        CHECK(l.markers[0].box.width() == doctest::Approx(12));
        const LayoutLabel* fixedLabel = nullptr;
        const LayoutLabel* moved = nullptr;
        const LayoutLabel* title = nullptr;
        for (const LayoutLabel& lab : l.labels)
            (lab.text == "fixed" ? fixedLabel : lab.text == "moved" ? moved : title) = &lab;
        REQUIRE((fixedLabel && moved && title));
        CHECK(fixedLabel->box.x0 == doctest::Approx(108));
        CHECK(fixedLabel->box.height() == doctest::Approx(16));
        CHECK(fixedLabel->anchor.has_value());
        CHECK_FALSE(title->anchor.has_value());
        CHECK(moved->box.overlapArea(fixedLabel->box) == 0);
        CHECK(moved->box.overlapArea(l.markers[0].box) == 0);
        CHECK(l.markers[0].label >= 0);
        CHECK(checkLegibility(l, 200, 200).empty());
    }
}
