#include "app/scene/demo.h"

#include <cctype>
#include <cmath>
#include <optional>

#include "render/canvas.h"

namespace cdlab::demos {

namespace {

bool isWordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// True when the text holds "nan" or "inf" as a whole word, in any case, as printf and iostreams
// print a NaN or an infinity ("-nan", "inf", "NaN"); "infinite" or "Finance" do not count.
bool printsNonFinite(const std::string& text) {
    for (const char* token : {"nan", "inf"})
        for (std::size_t i = 0; i + 3 <= text.size(); ++i) {
            const bool match = std::tolower(static_cast<unsigned char>(text[i])) == token[0] &&
                               std::tolower(static_cast<unsigned char>(text[i + 1])) == token[1] &&
                               std::tolower(static_cast<unsigned char>(text[i + 2])) == token[2];
            if (match && (i == 0 || !isWordChar(text[i - 1])) && (i + 3 == text.size() || !isWordChar(text[i + 3])))
                return true;
        }
    return false;
}

// The first non-finite number in `value`: its JSON path and its value.
struct NonFinite {
    std::string path;
    double value = 0;
};
std::optional<NonFinite> firstNonFinite(const Json& value, const std::string& path) {
    if (value.is_number_float()) {
        if (std::isfinite(value.get<double>())) return std::nullopt;
        return NonFinite{path, value.get<double>()};
    }
    if (value.is_array()) {
        for (std::size_t i = 0; i < value.size(); ++i)
            if (auto bad = firstNonFinite(value[i], path + "[" + std::to_string(i) + "]")) return bad;
    } else if (value.is_object()) {
        for (auto it = value.begin(); it != value.end(); ++it)
            if (auto bad = firstNonFinite(it.value(), path + "." + it.key())) return bad;
    }
    return std::nullopt;
}

}  // namespace

void requireFiniteOutput(const SceneCommon& scene, const DemoOutput& out, const std::vector<std::string>& drawnTexts) {
    const std::string why = " (the scene's numbers overflow double precision: see the limits in docs/scenes.md)";
    if (auto bad = firstNonFinite(out.trace, "$"))
        throw InputError(scene.file + ": trace " + bad->path + " is " + (std::isnan(bad->value) ? "NaN" : "infinite") +
                         why);
    for (const Frame& f : out.frames)
        if (printsNonFinite(f.caption))
            throw InputError(scene.file + ": frame '" + f.name + "': caption \"" + f.caption +
                             "\" prints a NaN or an infinity" + why);
    for (const std::string& text : drawnTexts)
        if (printsNonFinite(text))
            throw InputError(scene.file + ": a frame's text \"" + text + "\" prints a NaN or an infinity" + why);
}

bool numericOnly(const RunContext& context, DemoOutput& out) {
    if (context.gl) return false;
    out.skipped.push_back("all drawing (no GL context)");
    return true;
}

DemoOutput PreparedScene::run(const RunContext& context) const {
    render::drawnTextLog().clear();
    DemoOutput out = execute(context);
    requireFiniteOutput(common_, out, render::drawnTextLog());
    return out;
}

namespace {

// "gjk frames need an image of at least 320 x 240"; a range with one size is a fixed layout.
void requireImageSize(const ObjectReader& scene, const SceneCommon& common, const SceneFormat& format) {
    const ImageSizeRange& range = format.imageSize;
    const int w = common.image.width, h = common.image.height;
    const bool bounded = range.maxWidth > 0 && range.maxHeight > 0;
    if (w >= range.minWidth && h >= range.minHeight && (!bounded || (w <= range.maxWidth && h <= range.maxHeight)))
        return;
    const auto size = [](int width, int height) { return std::to_string(width) + " x " + std::to_string(height); };
    const std::string what = common.demo + " " + format.imageNoun;
    if (bounded && range.minWidth == range.maxWidth && range.minHeight == range.maxHeight)
        scene.node().fail(what + " have a fixed layout: image must be " + size(range.minWidth, range.minHeight));
    if (bounded)
        scene.node().fail(what + " need an image between " + size(range.minWidth, range.minHeight) + " and " +
                          size(range.maxWidth, range.maxHeight));
    scene.node().fail(what + " need an image of at least " + size(range.minWidth, range.minHeight));
}

}  // namespace

std::unique_ptr<PreparedScene> Demo::prepare(const Json& json, const std::string& file) const {
    ObjectReader reader(JsonNode(json, "$", file));
    const SceneFormat format = sceneFormat();
    std::unique_ptr<PreparedScene> scene =
        readScene(reader, readSceneCommon(reader, file, format.layers, format.layers, format.defaultImage));
    requireImageSize(reader, scene->common(), format);
    // The frames' sizes and count at the scene's own scale, before anything is drawn.
    checkImageBudget(scene->common(), 0);
    return scene;
}

}  // namespace cdlab::demos
