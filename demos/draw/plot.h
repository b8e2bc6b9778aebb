// Small 2D plots drawn with cdlab's own renderer (render/canvas.h): log-log scatter / line plots
// with decade ticks (Pareto fronts, error vs parameter) and decade histograms of errors.
// Pixel layout: title on top, plot area with axes and labels, legend in the upper right corner
// of the plot area, subtitle (caption) at the bottom.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

struct PlotOptions {
    std::string title, subtitle, xLabel, yLabel;
    int width = 1280, height = 768;  ///< layout units (output pixels at scale 1)
    int scale = 1;                   ///< print scale: pixels, text and lines times this
    int legendWidth = 300;           ///< pixels right of the plot area for the legend
    /// Values <= floor (and 0) are drawn at the floor on a log axis (errors of exactly 0).
    double xFloor = 1e-18, yFloor = 1e-18;
    bool logX = true, logY = true;
    /// Horizontal reference lines (value, label), dashed.
    std::vector<std::pair<double, std::string>> hLines;
};

struct SceneCommon;  // app/scene/scene.h

/// Options of a plot as large as the scene's image, at print scale `scale`, titled with the scene's
/// title (the figures' plots: the grid trade-off, the accuracy sweep, the impulse sweeps...).
PlotOptions scenePlotOptions(const SceneCommon& scene, int scale);

struct PlotSeries {
    std::string label;
    int style = 0;      ///< colour and marker: categorical colour `style`, marker shape style % 4
    bool line = false;  ///< connect the points in the given order
    bool markers = true;
    std::vector<std::pair<double, double>> points;  ///< (x, y) in data units
    /// Optional per-point labels drawn beside the markers (same size as points, or empty).
    std::vector<std::string> pointLabels;
};

/// A round tick step for a linear axis over `span`: 1, 2 or 5 times a power of ten, the smallest
/// giving at most `intervals` intervals (the V-Clip distance plot, EPA's bounds plot).
double roundTickStep(double span, int intervals);

/// Two bounds closing on an answer, per iteration (EPA's depth, GJK's distance): linear axes from a
/// round tick below the data to one above, the upper bound and the lower bound as lines with
/// markers, a legend naming each, the demo's title and a caption (every number from the trace).
struct BoundsPlot {
    std::vector<int> iterations;
    std::vector<double> lower, upper;  ///< one each per iteration
    std::string xLabel, yLabel, upperName, lowerName, title, caption;
};
render::Image drawBoundsPlot(render::GlContext& gl, int width, int height, int scale, const BoundsPlot& plot);

/// Scatter / line plot on log (or linear) axes with decade ticks, labels and a legend.
render::Image drawLogLogPlot(render::GlContext& gl, const PlotOptions& options, const std::vector<PlotSeries>& series);

/// Histograms of positive values (errors) in decade bins from options.xFloor to the largest value,
/// y = fraction of the values per bin (linear axis); values <= xFloor (and 0) go into the first
/// bin. One step outline per series (label, values).
render::Image drawDecadeHistogram(render::GlContext& gl, const PlotOptions& options,
                                  const std::vector<std::pair<std::string, std::vector<double>>>& series);

}  // namespace cdlab::demos
