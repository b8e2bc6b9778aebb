#include "app/harness/layout_json.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace cdlab::demos {

namespace {

// Tenths of a pixel: enough for a legibility check, stable across platforms' last bits.
double px(double v) { return std::round(v * 10.0) / 10.0 + 0.0; }

Json boxJson(const render::Box& b) { return Json::array({px(b.x0), px(b.y0), px(b.x1), px(b.y1)}); }

// 0xRRGGBB as "#RRGGBB" (a series', a step feature's colour).
std::string hexColor(unsigned rgb) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "#%06X", rgb & 0xFFFFFFu);
    return hex;
}

}  // namespace

Json layoutJson(const render::Image& image) {
    const render::FigureLayout& l = image.layout;
    Json panels = Json::array(), labels = Json::array(), markers = Json::array();
    for (const render::Box& p : l.panels) panels.push_back(boxJson(p));
    for (const render::LayoutLabel& t : l.labels)
        labels.push_back({{"text", t.text},
                          {"box", boxJson(t.box)},
                          {"anchor", t.anchor ? Json::array({px(t.anchor->x()), px(t.anchor->y())}) : Json()},
                          {"size_px", px(t.lineHeight)}});
    for (const render::LayoutMarker& m : l.markers)
        markers.push_back({{"box", boxJson(m.box)}, {"label", m.label >= 0 ? Json(m.label) : Json()}});
    // [x0, y0, x1, y1, width], plus the label index for a label's own leader line, plus (the 6th
    // null when it is no leader) the index of the label naming the body it outlines.
    Json strokes = Json::array();
    for (const render::LayoutStroke& k : l.strokes) {
        Json s = Json::array({px(k.a.x()), px(k.a.y()), px(k.b.x()), px(k.b.y()), px(k.width)});
        if (k.leaderOf >= 0 || k.outlineOf >= 0) s.push_back(k.leaderOf >= 0 ? Json(k.leaderOf) : Json());
        if (k.outlineOf >= 0) s.push_back(k.outlineOf);
        strokes.push_back(std::move(s));
    }
    Json out = {{"width", image.width}, {"height", image.height}, {"panels", panels},
                {"labels", labels},     {"markers", markers},     {"strokes", strokes}};
    if (!l.quantities.empty()) {  // only where a frame names one: older manifests stay as they were
        Json quantities = Json::array();
        for (const render::LayoutQuantity& q : l.quantities) quantities.push_back({{"name", q.name}, {"px", px(q.px)}});
        out["quantities"] = std::move(quantities);
    }
    if (!l.bodies.empty()) {  // only where a frame notes its bodies (Canvas::noteBody)
        Json bodies = Json::array();
        for (const render::LayoutBody& b : l.bodies) {
            Json outline = Json::array();
            for (const Eigen::Vector2d& p : b.outline) outline.push_back(Json::array({px(p.x()), px(p.y())}));
            Json body = {{"name", b.name}, {"outline", std::move(outline)}};
            if (!b.apartFrom.empty()) body["apart_from"] = b.apartFrom;
            bodies.push_back(std::move(body));
        }
        out["bodies"] = std::move(bodies);
    }
    // Cosines to three decimals: the rules' thresholds are two.
    const auto milli = [](double v) { return std::round(v * 1000.0) / 1000.0 + 0.0; };
    if (!l.features.empty()) {  // only where a frame notes a highlighted feature (Canvas::noteFeature)
        Json features = Json::array();
        for (const render::LayoutFeature& f : l.features) {
            Json feature = {{"name", f.name},
                            {"dimension", f.dimension},
                            {"facing", milli(f.facing)},
                            {"foreshortening", milli(f.foreshortening)},
                            {"filled", f.filled},
                            {"step", f.step},
                            {"at", Json::array({px(f.at.x()), px(f.at.y())})}};
            if (f.rgb >= 0) {  // a step's feature judged by its colour (StepFeatureFaded)
                Json samples = Json::array();
                for (const Eigen::Vector2d& p : f.samples) samples.push_back(Json::array({px(p.x()), px(p.y())}));
                feature["color"] = hexColor(unsigned(f.rgb));
                feature["samples"] = std::move(samples);
            }
            features.push_back(std::move(feature));
        }
        out["features"] = std::move(features);
    }
    if (!l.axes.empty()) {  // plots (Canvas::noteAxis)
        Json axes = Json::array();
        for (const render::LayoutAxis& a : l.axes)
            axes.push_back({{"from", Json::array({px(a.a.x()), px(a.a.y())})},
                            {"to", Json::array({px(a.b.x()), px(a.b.y())})},
                            {"log", a.log}});
        out["axes"] = std::move(axes);
    }
    if (!l.series.empty()) {  // plots (Canvas::noteSeries)
        Json series = Json::array();
        for (const render::LayoutSeries& k : l.series)
            series.push_back({{"name", k.name}, {"color", hexColor(k.rgb)}, {"at", Json::array({px(k.at.x()), px(k.at.y())})}});
        out["series"] = std::move(series);
    }
    return out;
}

}  // namespace cdlab::demos
