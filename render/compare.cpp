#include "render/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace cdlab::render {

namespace {
std::string format(const char* fmt, auto... args) {
    char buf[256];
    std::snprintf(buf, sizeof buf, fmt, args...);
    return buf;
}
}  // namespace

CompareResult compareImages(const Image& actual, const Image& expected, const CompareTolerance& tol) {
    CompareResult r;
    r.applied = tol;
    r.actualWidth = actual.width;
    r.actualHeight = actual.height;
    r.expectedWidth = expected.width;
    r.expectedHeight = expected.height;
    if (actual.width != expected.width || actual.height != expected.height) {
        r.sizeMismatch = true;
        r.psnr = 0.0;
        return r;
    }
    r.totalPixels = std::int64_t(expected.width) * expected.height;
    if (pixelHash(actual) == pixelHash(expected) && actual.rgba == expected.rgba) {
        r.exact = r.passed = true;
        r.psnr = std::numeric_limits<double>::infinity();
        return r;
    }
    double sumSq = 0.0;
    for (int y = 0; y < expected.height; ++y)
        for (int x = 0; x < expected.width; ++x) {
            const std::uint8_t* a = actual.pixel(x, y);
            const std::uint8_t* e = expected.pixel(x, y);
            int pixelMax = 0;
            for (int c = 0; c < 4; ++c) {
                const int d = std::abs(int(a[c]) - int(e[c]));
                pixelMax = std::max(pixelMax, d);
                sumSq += double(d) * d;
            }
            if (pixelMax > 0) ++r.anyDiffPixels;
            if (pixelMax > tol.maxChannelDelta) ++r.diffPixels;
            if (pixelMax > r.maxDelta) {  // first (top-most, left-most) location of the maximum
                r.maxDelta = pixelMax;
                r.maxDeltaX = x;
                r.maxDeltaY = y;
            }
        }
    const double mse = sumSq / (double(r.totalPixels) * 4.0);
    r.rms = std::sqrt(mse);
    r.psnr = mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : std::numeric_limits<double>::infinity();
    const double fraction = r.totalPixels > 0 ? double(r.diffPixels) / double(r.totalPixels) : 0.0;
    r.passed = r.diffPixels <= tol.maxDiffPixels || fraction <= tol.maxDiffFraction;
    return r;
}

std::string CompareResult::summary() const {
    const std::string tolerance =
        format("tolerance: channel delta <= %d, differing pixels <= %lld or <= %.4g%%", applied.maxChannelDelta,
               (long long)applied.maxDiffPixels, applied.maxDiffFraction * 100.0);
    if (sizeMismatch)
        return format("FAIL size mismatch: actual %dx%d, expected %dx%d; ", actualWidth, actualHeight, expectedWidth,
                      expectedHeight) +
               tolerance;
    if (exact) return format("PASS exact (identical pixel hash, %dx%d); ", expectedWidth, expectedHeight) + tolerance;
    const double pct = totalPixels > 0 ? 100.0 * double(diffPixels) / double(totalPixels) : 0.0;
    return format(
               "%s %lld of %lld pixels differ beyond tolerance (%.4g%%), %lld differ at all; max delta %d at (%d,%d); "
               "RMS %.3f; PSNR %.2f dB; ",
               passed ? "PASS fuzzy:" : "FAIL:", (long long)diffPixels, (long long)totalPixels, pct,
               (long long)anyDiffPixels, maxDelta, maxDeltaX, maxDeltaY, rms, psnr) +
           tolerance;
}

Image diffImage(const Image& actual, const Image& expected, int gain) {
    const int w = std::max(actual.width, expected.width), h = std::max(actual.height, expected.height);
    Image out(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* o = out.pixel(x, y);
            const bool inA = x < actual.width && y < actual.height;
            const bool inE = x < expected.width && y < expected.height;
            if (!inA || !inE) {  // outside one of them: solid red
                o[0] = 255, o[1] = 0, o[2] = 0, o[3] = 255;
                continue;
            }
            const std::uint8_t* a = actual.pixel(x, y);
            const std::uint8_t* e = expected.pixel(x, y);
            // Dimmed expected: its luminance squeezed into 200..255 so the diff stands out.
            const double lum = 0.299 * e[0] + 0.587 * e[1] + 0.114 * e[2];
            const double base = 200.0 + lum * (55.0 / 255.0);
            int d = 0;
            for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int(a[c]) - int(e[c])));
            // Amplified; any difference at all gets at least 64 so a 1-level change is visible.
            const int amp = d == 0 ? 0 : std::clamp(d * std::max(gain, 1), 64, 255);
            const double t = amp / 255.0;  // blend the base towards pure magenta-red
            o[0] = std::uint8_t(std::lround(base + (230.0 - base) * t));
            o[1] = std::uint8_t(std::lround(base * (1.0 - t)));
            o[2] = std::uint8_t(std::lround(base + (60.0 - base) * t));
            o[3] = 255;
        }
    return out;
}

std::string htmlEscape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    return out;
}

void writeHtmlReport(const std::string& path, const std::vector<ReportEntry>& entries) {
    std::string html =
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>cdlab golden-image "
        "report</title>\n"
        "<style>\n"
        "body{font-family:sans-serif;margin:1.5em;background:#fafafa;color:#1a1a1f}\n"
        "section{background:#fff;border:1px solid #ddd;margin:0 0 1.5em 0;padding:0.8em}\n"
        "h2{font-size:1.1em;margin:0 0 0.3em 0}\n"
        "p.summary{font-family:monospace;font-size:0.85em;white-space:pre-wrap}\n"
        ".row{display:flex;gap:0.8em;flex-wrap:wrap}\n"
        "figure{margin:0}figcaption{font-size:0.85em;color:#555}\n"
        "img{max-width:30vw;border:1px solid #ccc;image-rendering:pixelated}\n"
        ".missing{width:200px;height:120px;border:1px dashed #c00;color:#c00;display:flex;align-items:center;"
        "justify-content:center}\n"
        "</style>\n</head>\n<body>\n";
    std::size_t images = 0;
    for (const ReportEntry& e : entries) images += !e.actualPng.empty();
    html += "<h1>cdlab golden-image report</h1>\n<p>" + std::to_string(entries.size()) +
            (entries.size() == 1 ? " failure" : " failures") + " (" + std::to_string(images) + " of images, " +
            std::to_string(entries.size() - images) + " of traces or legibility).</p>\n";
    auto figure = [](const std::string& src, const char* caption) {
        std::string f = "<figure>";
        if (src.empty()) f += "<div class=\"missing\">none</div>";
        else
            f +=
                "<a href=\"" + htmlEscape(src) + "\"><img src=\"" + htmlEscape(src) + "\" alt=\"" + caption + "\"></a>";
        return f + "<figcaption>" + caption + "</figcaption></figure>";
    };
    for (const ReportEntry& e : entries) {
        html += "<section>\n<h2>" + htmlEscape(e.name) + "</h2>\n<p class=\"summary\">" + htmlEscape(e.summary) + "</p>\n";
        if (!e.actualPng.empty())  // a trace or legibility failure has no pictures, only its text
            html += "<div class=\"row\">" + figure(e.actualPng, "actual") + figure(e.expectedPng, "expected") +
                    figure(e.diffPng, "diff") + "</div>\n";
        html += "</section>\n";
    }
    html += "</body>\n</html>\n";
    writeFileAtomic(path, html);
}

}  // namespace cdlab::render
