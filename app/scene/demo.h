// The interface every demo implements (the catalogue of all demos is app/catalog/catalog.h). A demo reads its scene
// keys (prepare: validation only, errors before any output), then runs its core algorithm once and draws only what the
// scene's layers ask for (run). Numeric-only runs pass no GL context: nothing is drawn.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

struct Frame {
    std::string name;     // file stem: "plane", "step_03", "contact_sheet"
    std::string caption;  // one line for galleries and contact sheets
    render::Image image;
};

struct DemoOutput {
    std::vector<Frame> frames;
    Json trace = Json::object();       // the algorithm's results per step (numbers compared with a tolerance)
    std::vector<std::string> skipped;  // what the scene did not need and was not computed (for --profile)
    std::vector<std::pair<std::string, std::string>>
        files;  // name -> bytes (e.g. "animation.gif"); not golden-compared
};

struct RunContext {
    render::GlContext* gl = nullptr;  // null: numeric only, draw nothing
    int scaleOverride = 0;            // > 0 replaces the scene's supersampling factor
    bool stepsOverride = false;       // force per-step frames
};

class PreparedScene {
public:
    virtual ~PreparedScene() = default;
    /// Runs the scene (execute) and checks what it produced: a NaN or an infinity anywhere in the
    /// trace, a caption or a text drawn on a frame is an InputError naming the scene file and the
    /// quantity (the trace's JSON path, or the text) — never a figure that says "E = -nan J".
    DemoOutput run(const RunContext& context) const;
    const SceneCommon& common() const { return common_; }

protected:
    explicit PreparedScene(SceneCommon common) : common_(std::move(common)) {}
    /// The demo's work: its core algorithm once, then what the scene's layers ask to draw.
    virtual DemoOutput execute(const RunContext& context) const = 0;
    SceneCommon common_;
};

/// True for a numeric-only run (no GL context): nothing is drawn, and out.skipped says so.
bool numericOnly(const RunContext& context, DemoOutput& out);

/// The check PreparedScene::run applies, on its own (throws InputError naming `scene.file`).
void requireFiniteOutput(const SceneCommon& scene, const DemoOutput& out, const std::vector<std::string>& drawnTexts);

/// The image sizes a demo's layout can draw; 0 means no bound.
struct ImageSizeRange {
    int minWidth = 0, minHeight = 0;
    int maxWidth = 0, maxHeight = 0;
};

/// What a demo's scenes hold besides their own keys: the layers a scene may ask for (all of them by
/// default), the image size where the scene gives none, the sizes the layout can draw and what the
/// demo calls its images in the error that refuses one ("frames", "plots").
struct SceneFormat {
    std::vector<std::string> layers;
    ImageSettings defaultImage;
    ImageSizeRange imageSize;
    std::string imageNoun = "frames";
};

class Demo {
public:
    virtual ~Demo() = default;
    virtual std::string name() const = 0;         // "voronoi_triangle" (= golden/ folder, = demo_<name> executable)
    virtual std::string description() const = 0;  // one line
    /// Reads the scene (the common keys, then this demo's keys), validates everything, computes
    /// nothing heavy; the image size is checked last, against sceneFormat().imageSize.
    std::unique_ptr<PreparedScene> prepare(const Json& json, const std::string& file) const;

protected:
    virtual SceneFormat sceneFormat() const = 0;
    /// Reads this demo's keys from the scene object (the common ones are in `common`) and calls
    /// scene.finish(), so that a key nobody reads is an error.
    virtual std::unique_ptr<PreparedScene> readScene(ObjectReader& scene, SceneCommon common) const = 0;
};

}  // namespace cdlab::demos
