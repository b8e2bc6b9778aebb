// The scene format shared by every demo: common keys (read here) + demo-specific keys (read by
// the demo from the same ObjectReader, so unknown keys anywhere are errors). See docs/scenes.md.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "app/scene/json_reader.h"
#include "render/camera.h"
#include "render/compare.h"

namespace cdlab::demos {

struct ImageSettings {
    int width = 1024;
    int height = 1024;
    int scale = 1;  // supersampling factor (print quality: 2)
};

/// How close a run must be to its goldens.
struct GoldenTolerance {
    render::CompareTolerance image;  // default: exact pixels
    double traceAbsolute = 1e-9;     // numbers in the trace: |a - e| <= abs + rel * |e|
    double traceRelative = 1e-9;
};

/// What a scene's run may draw, declared by its demo while it reads the scene (before anything is
/// drawn) and checked by checkImageBudget: the most frames it draws without and with per-step
/// frames (views, plots and the contact sheet included), and the width of its widest frame in
/// layout pixels where a frame is wider than the image (0: none is).
struct FrameBudget {
    int frames = 1;
    int framesWithSteps = 1;
    int frameWidth = 0;
};

/// The keys every scene has.
struct SceneCommon {
    std::string file;  // path of the scene JSON
    std::string demo;  // "voronoi_triangle", ...
    std::string name;  // file stem: "regions"
    std::string title;
    std::string caption;
    ImageSettings image;
    std::optional<render::Camera> camera;
    std::set<std::string> layers;
    bool steps = false;  // one frame per step + a contact sheet
    GoldenTolerance golden;
    FrameBudget frames;  // set by the demo's readScene

    bool hasLayer(const std::string& layer) const { return layers.count(layer) != 0; }
};

/// True for a name that stays inside the folder it is joined to: [A-Za-z0-9_-][A-Za-z0-9_.-]*,
/// at most 255 bytes (so never "", ".", "..", a hidden name, nor anything with '/').
bool isPlainName(const std::string& name);

/// Reads the common keys; `allowedLayers`, `defaultLayers` and the image size used where the
/// scene gives none (`defaultImage`, per field) come from the demo.
SceneCommon readSceneCommon(ObjectReader& reader, const std::string& file,
                            const std::vector<std::string>& allowedLayers,
                            const std::vector<std::string>& defaultLayers, const ImageSettings& defaultImage = {});

render::Camera readCamera(const JsonNode& node);

/// Fails (InputError naming the scene file and $.image) when the scene's frames, drawn at
/// `scaleOverride` (> 0: the command line's --scale; 0: the scene's own) and with per-step frames
/// when the scene or `stepsOverride` (--steps) asks for them, break a limit: a frame above
/// kMaxSupersampledPixels or wider than kMaxImageSide, or all of them together above
/// kMaxScenePixels (scene.frames says how many and how wide). Demo::prepare checks it at the scene's
/// own scale; a command with --scale or --steps checks it again.
void checkImageBudget(const SceneCommon& scene, int scaleOverride, bool stepsOverride = false);

/// Scene files: golden/<demo>/<scene>.json, sorted.
std::vector<std::string> findSceneFiles(const std::string& goldenDir);

/// "golden/voronoi_triangle/regions.json" -> "voronoi_triangle/regions".
std::string sceneId(const SceneCommon& scene);

}  // namespace cdlab::demos
