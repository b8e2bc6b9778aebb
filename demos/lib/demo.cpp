#include "demos/lib/demo.h"

#include <cctype>
#include <cmath>
#include <optional>

#include "render/canvas.h"

#include "demos/lib/accuracy_demo.h"
#include "demos/lib/bounding_volumes_demo.h"
#include "demos/lib/bvh_demo.h"
#include "demos/lib/drop_demo.h"
#include "demos/lib/epa_demo.h"
#include "demos/lib/gjk_demo.h"
#include "demos/lib/lin_canny_demo.h"
#include "demos/lib/polyhedron_plane_demo.h"
#include "demos/lib/space_partition_demo.h"
#include "demos/lib/sweep_and_prune_demo.h"
#include "demos/lib/vclip_demo.h"
#include "demos/lib/voronoi_demo.h"

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
        throw InputError(scene.file + ": trace " + bad->path + " is " + (std::isnan(bad->value) ? "NaN" : "infinite") + why);
    for (const Frame& f : out.frames)
        if (printsNonFinite(f.caption))
            throw InputError(scene.file + ": frame '" + f.name + "': caption \"" + f.caption + "\" prints a NaN or an infinity" + why);
    for (const std::string& text : drawnTexts)
        if (printsNonFinite(text))
            throw InputError(scene.file + ": a frame's text \"" + text + "\" prints a NaN or an infinity" + why);
}

DemoOutput PreparedScene::run(const RunContext& context) const {
    render::drawnTextLog().clear();
    DemoOutput out = execute(context);
    requireFiniteOutput(common_, out, render::drawnTextLog());
    return out;
}

const std::vector<const Demo*>& allDemos() {
    static const std::vector<const Demo*> demos = {&voronoiDemo(), &gjkDemo(), &epaDemo(), &vclipDemo(), &linCannyDemo(), &polyhedronPlaneDemo(), &dropDemo(), &accuracyDemo(), &spacePartitionDemo(), &boundingVolumesDemo(), &bvhDemo(), &sweepAndPruneDemo()};
    return demos;
}

const Demo* findDemo(const std::string& name) {
    for (const Demo* d : allDemos())
        if (d->name() == name) return d;
    return nullptr;
}

std::unique_ptr<PreparedScene> loadScene(const std::string& file) { return prepareScene(readJsonFile(file), file); }

std::unique_ptr<PreparedScene> loadSceneText(const std::string& text, const std::string& source) {
    return prepareScene(parseJson(text, source), source);
}

std::unique_ptr<PreparedScene> prepareScene(const Json& json, const std::string& file) {
    JsonNode root(json, "$", file);
    if (!root.isObject()) root.fail("a scene must be a JSON object, got " + JsonNode::describe(json));
    auto it = json.find("demo");
    if (it == json.end()) root.fail("missing required key 'demo'");
    JsonNode demoNode(*it, "$.demo", file);
    std::vector<std::string> names;
    for (const Demo* d : allDemos()) names.push_back(d->name());
    const Demo* demo = findDemo(demoNode.asEnum(names));
    return demo->prepare(json, file);
}

}  // namespace cdlab::demos
