// Golden comparison: exact hash match, fuzzy tolerance, statistics, diff image, HTML report.
#include <doctest/doctest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "render/compare.h"

using namespace cdlab::render;
namespace fs = std::filesystem;

namespace {

/// A figure-like test card: white page, a dark disc, a blue bar, a grey ramp.
Image card(int w, int h) {
    Image im(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = im.pixel(x, y);
            p[0] = p[1] = p[2] = 255;
            p[3] = 255;
            const double dx = x - w * 0.3, dy = y - h * 0.4;
            if (dx * dx + dy * dy < 0.04 * w * w) p[0] = p[1] = p[2] = 30;
            if (y > h * 0.7 && y < h * 0.8) p[0] = 0, p[1] = 114, p[2] = 178;
            if (x > w * 0.8) p[0] = p[1] = p[2] = std::uint8_t(255 * y / h);
        }
    return im;
}

Image shiftRight(const Image& im) {
    Image out = im;
    for (int y = 0; y < im.height; ++y)
        for (int x = 1; x < im.width; ++x)
            for (int c = 0; c < 4; ++c) out.pixel(x, y)[c] = im.pixel(x - 1, y)[c];
    return out;
}

}  // namespace

TEST_SUITE("render/compare") {
    TEST_CASE("identical images match exactly and say so") {
        const Image a = card(64, 48);
        const CompareResult r = compareImages(a, a, {});
        CHECK(r.exact);
        CHECK(r.passed);
        CHECK(r.diffPixels == 0);
        CHECK(std::isinf(r.psnr));
        CHECK(r.summary().find("exact") != std::string::npos);
    }

    TEST_CASE("statistics against a hand computation") {
        // 4x4 image, one channel of one pixel off by 255: 64 channel samples.
        Image a(4, 4), b(4, 4);
        b.pixel(2, 1)[1] = 255;
        const CompareResult r = compareImages(a, b, {});
        CHECK_FALSE(r.exact);
        CHECK_FALSE(r.passed);
        CHECK(r.diffPixels == 1);
        CHECK(r.anyDiffPixels == 1);
        CHECK(r.maxDelta == 255);
        CHECK(r.maxDeltaX == 2);
        CHECK(r.maxDeltaY == 1);
        CHECK(r.rms == doctest::Approx(255.0 / 8.0));               // sqrt(255^2 / 64)
        CHECK(r.psnr == doctest::Approx(10.0 * std::log10(64.0)));  // 255^2 / mse = 64
        const std::string s = r.summary();
        for (const char* part : {"FAIL", "1 of 16", "max delta 255 at (2,1)", "RMS", "PSNR", "tolerance"})
            CHECK_MESSAGE(s.find(part) != std::string::npos, s);
    }

    TEST_CASE("fuzzy tolerance: channel delta, pixel count and fraction") {
        const Image a = card(50, 40);
        Image b = a;
        for (int i = 0; i < 5; ++i) b.pixel(10 + i, 10)[0] ^= 2;  // 5 pixels off by 2
        CHECK_FALSE(compareImages(b, a, {}).passed);
        CHECK(compareImages(b, a, {2, 0, 0.0}).passed);  // delta 2 allowed
        const CompareResult r1 = compareImages(b, a, {1, 0, 0.0});
        CHECK_FALSE(r1.passed);
        CHECK(r1.diffPixels == 5);
        CHECK(compareImages(b, a, {1, 5, 0.0}).passed);
        CHECK_FALSE(compareImages(b, a, {1, 4, 0.0}).passed);
        CHECK(compareImages(b, a, {1, 0, 5.0 / 2000.0}).passed);  // 5 of 2000 pixels
        CHECK_FALSE(compareImages(b, a, {1, 0, 4.0 / 2000.0}).passed);
        CHECK(compareImages(b, a, {1, 5, 0.0}).summary().find("PASS fuzzy") != std::string::npos);
    }

    TEST_CASE("the harness can fail: a few perturbed pixels and a 1-pixel shift are rejected") {
        const Image golden = card(120, 90);
        Image few = golden;
        few.pixel(5, 5)[2] = 0;
        few.pixel(60, 45)[0] = 200;
        few.pixel(119, 89)[1] ^= 1;  // even a 1-level change in the corner
        CHECK_FALSE(compareImages(few, golden, {}).passed);
        const Image shifted = shiftRight(golden);
        const CompareResult r = compareImages(shifted, golden, {});
        CHECK_FALSE(r.passed);
        CHECK(r.diffPixels > 20);  // the disc's and bar's vertical edges
        // A loose-looking fuzzy tolerance still catches the shift.
        CHECK_FALSE(compareImages(shifted, golden, {8, 16, 0.0}).passed);
    }

    TEST_CASE("size mismatch never passes") {
        const CompareResult r = compareImages(card(10, 10), card(10, 11), {255, 1000, 1.0});
        CHECK(r.sizeMismatch);
        CHECK_FALSE(r.passed);
        CHECK(r.summary().find("10x10") != std::string::npos);
        CHECK(r.summary().find("10x11") != std::string::npos);
    }

    TEST_CASE("diffImage: untouched pixels are a light grey, differences red, outside areas pure red") {
        const Image a = card(30, 20);
        Image b = a;
        b.pixel(7, 3)[0] ^= 1;  // the smallest possible difference must still show
        const Image d = diffImage(b, a);
        REQUIRE(d.width == 30);
        const std::uint8_t* same = d.pixel(0, 0);
        CHECK(same[0] == same[1]);  // grey
        CHECK(int(same[0]) >= 200);
        const std::uint8_t* diff = d.pixel(7, 3);
        CHECK(int(diff[0]) - int(diff[1]) > 40);  // visibly red
        const Image u = diffImage(card(30, 20), card(20, 25));
        CHECK(u.width == 30);
        CHECK(u.height == 25);
        CHECK(int(u.pixel(25, 5)[0]) == 255);
        CHECK(int(u.pixel(25, 5)[1]) == 0);
        CHECK(int(u.pixel(5, 22)[1]) == 0);
    }

    TEST_CASE("HTML report: one static page, escaped text, relative paths") {
        const fs::path dir = fs::temp_directory_path() / ("cdlab_compare_test_" + std::to_string(::getpid()));
        const std::string page = (dir / "report.html").string();
        writeHtmlReport(page, {{"gjk/<simplex> & \"steps\"", "actual/a.png", "expected/a.png", "diff/a.png",
                                "FAIL: 3 of 4 pixels differ"},
                               {"missing/golden", "actual/b.png", "", "", "golden missing"}});
        std::ifstream in(page);
        const std::string html{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        CHECK(html.find("<!DOCTYPE html>") == 0);
        CHECK(html.find("gjk/&lt;simplex&gt; &amp; &quot;steps&quot;") != std::string::npos);
        CHECK(html.find("<simplex>") == std::string::npos);
        CHECK(html.find("src=\"actual/a.png\"") != std::string::npos);
        CHECK(html.find("src=\"diff/a.png\"") != std::string::npos);
        CHECK(html.find("<script") == std::string::npos);
        CHECK(html.find("golden missing") != std::string::npos);
        int files = 0;
        for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
        CHECK(files == 1);  // no temp file left
        fs::remove_all(dir);
        CHECK(htmlEscape("a<b>&'\"") == "a&lt;b&gt;&amp;&#39;&quot;");
    }
}
