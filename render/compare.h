// Golden-image comparison on decoded pixels, and the HTML failure report.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/image.h"

namespace cdlab::render {

/// How far an image may differ from its golden and still pass. Default: exact.
struct CompareTolerance {
    int maxChannelDelta = 0;         // a pixel "differs" if any channel differs by more than this
    std::int64_t maxDiffPixels = 0;  // pass if differing pixels <= this ...
    double maxDiffFraction = 0.0;    // ... or differing pixels / total <= this
};

struct CompareResult {
    bool sizeMismatch = false;
    bool exact = false;                  // pixel hashes equal
    bool passed = false;                 // exact, or within tolerance
    std::int64_t diffPixels = 0;         // pixels with some channel delta > maxChannelDelta
    std::int64_t anyDiffPixels = 0;      // pixels with any delta at all
    int maxDelta = 0;                    // largest channel delta ...
    int maxDeltaX = -1, maxDeltaY = -1;  // ... and where
    double rms = 0.0;                    // over all channels, 0..255 scale
    double psnr = 0.0;                   // dB; +inf when identical
    CompareTolerance applied;
    std::int64_t totalPixels = 0;  // of expected (0 on size mismatch)
    int actualWidth = 0, actualHeight = 0, expectedWidth = 0, expectedHeight = 0;
    /// One line: what was applied and what was measured.
    std::string summary() const;
};

/// Exact pixel-hash match first; otherwise measures every channel delta and applies `tol`.
/// Different sizes never pass (sizeMismatch = true, no pixel statistics).
CompareResult compareImages(const Image& actual, const Image& expected, const CompareTolerance& tol = {});

/// Per-pixel |a - b| amplified by `gain` (clamped), over a dimmed copy of `expected`, so small
/// differences are visible. Sizes may differ: the union canvas is used, outside areas red.
Image diffImage(const Image& actual, const Image& expected, int gain = 16);

struct ReportEntry {
    std::string name;         // e.g. "voronoi_triangle/regions"
    std::string actualPng;    // paths relative to the report's folder; empty: a trace or legibility failure
    std::string expectedPng;  // may be empty when the golden is missing
    std::string diffPng;      // may be empty
    std::string summary;      // CompareResult::summary() or the reason
};

/// Escapes & < > " ' for HTML text and attribute values.
std::string htmlEscape(const std::string& text);

/// Writes one static HTML page (no scripts, works offline) with every failure side by side.
void writeHtmlReport(const std::string& path, const std::vector<ReportEntry>& entries);

}  // namespace cdlab::render
