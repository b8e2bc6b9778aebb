#include "app/scene/scene.h"

#include <algorithm>
#include <filesystem>

#include "app/scene/scene_limits.h"

namespace cdlab::demos {

namespace fs = std::filesystem;

render::Camera readCamera(const JsonNode& node) {
    ObjectReader r(node);
    render::Camera cam;
    std::string projection = r.get("projection").asEnum({"perspective", "orthographic", "2d"});
    if (projection == "2d") {
        auto center = r.find("center");
        double cx = 0, cy = 0;
        if (center) {
            if (center->size() != 2) center->fail("expected [x, y]");
            cx = sceneCoordinate(center->at(0));
            cy = sceneCoordinate(center->at(1));
        }
        cam = render::Camera::twoD(cx, cy, sceneSize(r.get("height")));
    } else {
        cam.projection = projection == "perspective" ? render::Camera::Projection::Perspective
                                                     : render::Camera::Projection::Orthographic;
        if (auto n = r.find("eye")) cam.eye = sceneVec3(*n);
        if (auto n = r.find("target")) cam.target = sceneVec3(*n);
        if (auto n = r.find("up")) cam.up = sceneVec3(*n);
        if (auto n = r.find("fov")) cam.fovYDegrees = n->asPositive();
        if (auto n = r.find("height")) cam.viewHeight = sceneSize(*n);
        if ((cam.eye - cam.target).norm() == 0) node.fail("camera eye equals target");
        if ((cam.eye - cam.target).cross(cam.up).norm() == 0) node.fail("camera up is parallel to the view direction");
        if (cam.fovYDegrees >= 179) node.fail("camera fov must be below 179 degrees");
    }
    r.finish();
    return cam;
}

SceneCommon readSceneCommon(ObjectReader& r, const std::string& file, const std::vector<std::string>& allowedLayers,
                            const std::vector<std::string>& defaultLayers, const ImageSettings& defaultImage) {
    SceneCommon s;
    s.image = defaultImage;
    s.file = file;
    // The name becomes a folder (<out>/<demo>/<name>, golden/<demo>/<name>) where a run puts one:
    // sceneOutputDir refuses a name that is not plain ("...json" would name ".."), and `render
    // FILE --out DIR`, which names its folder itself, takes any file name.
    s.name = fs::path(file).stem().string();
    requireTextLengths(r.node());  // before any text is read
    s.demo = r.get("demo").asString();
    s.title = r.stringOr("title", s.name);
    s.caption = r.stringOr("caption", "");
    r.ignore("_comment");
    if (auto image = r.find("image")) {
        ObjectReader ir(*image);
        s.image.width = ir.find("width") ? ir.get("width").asInt(16, kMaxImageSide) : s.image.width;
        s.image.height = ir.find("height") ? ir.get("height").asInt(16, kMaxImageSide) : s.image.height;
        s.image.scale = ir.find("scale") ? ir.get("scale").asInt(1, 4) : s.image.scale;
        ir.finish();
        const double pixels = double(s.image.width) * s.image.height * s.image.scale * s.image.scale;
        requireAtMost(*image, pixels, kMaxSupersampledPixels, "width x height x scale² (supersampled pixels)",
                      "a frame costs ~115 bytes per supersampled pixel");
    }
    if (auto cam = r.find("camera")) s.camera = readCamera(*cam);
    if (auto layers = r.find("layers")) {
        for (const JsonNode& item : layers->items()) s.layers.insert(item.asEnum(allowedLayers));
    } else {
        s.layers.insert(defaultLayers.begin(), defaultLayers.end());
    }
    s.steps = r.boolOr("steps", false);
    if (auto golden = r.find("golden")) {
        ObjectReader g(*golden);
        if (auto n = g.find("max_channel_delta")) s.golden.image.maxChannelDelta = n->asInt(0, 255);
        if (auto n = g.find("max_diff_pixels")) s.golden.image.maxDiffPixels = n->asInt(0, 1 << 30);
        if (auto n = g.find("max_diff_fraction")) s.golden.image.maxDiffFraction = n->asNonNegative();
        if (auto n = g.find("trace_absolute")) s.golden.traceAbsolute = n->asNonNegative();
        if (auto n = g.find("trace_relative")) s.golden.traceRelative = n->asNonNegative();
        g.finish();
    }
    return s;
}

bool isPlainName(const std::string& name) {
    if (name.empty() || name.size() > 255) return false;
    const auto plainChar = [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
               c == '.';
    };
    if (name[0] == '.') return false;  // ".", "..", and hidden names
    return std::all_of(name.begin(), name.end(), plainChar);
}

void checkImageBudget(const SceneCommon& scene, int scaleOverride, bool stepsOverride) {
    const int scale = scaleOverride > 0 ? scaleOverride : scene.image.scale;
    const std::string where = scene.file + ": $.image: ";
    const auto count = [](double x) { return std::to_string(static_cast<long long>(x)); };
    const double pixels = double(scene.image.width) * scene.image.height * scale * scale;
    if (pixels > kMaxSupersampledPixels)
        throw InputError(where + std::to_string(scene.image.width) + " x " + std::to_string(scene.image.height) +
                         " at scale " + std::to_string(scale) + " is " + count(pixels) +
                         " supersampled pixels, above the limit of " + count(kMaxSupersampledPixels));
    // A frame wider than the image (drop: the view and a side view beside it) obeys the same limits.
    const int width = std::max(scene.image.width, scene.frames.frameWidth);
    const double framePixels = double(width) * scene.image.height * scale * scale;
    if (width > kMaxImageSide || framePixels > kMaxSupersampledPixels)
        throw InputError(where + "the " + scene.demo + " frames are " + std::to_string(width) + " x " +
                         std::to_string(scene.image.height) + " (wider than the image) at scale " +
                         std::to_string(scale) + ": above the limit of " + std::to_string(kMaxImageSide) +
                         " per side or " + count(kMaxSupersampledPixels) + " supersampled pixels");
    const bool steps = scene.steps || stepsOverride;
    const int frames = std::max(1, steps ? scene.frames.framesWithSteps : scene.frames.frames);
    const double total = frames * framePixels;
    if (total > kMaxScenePixels)
        throw InputError(where + std::to_string(frames) + " frames" + (steps ? " (with per-step frames)" : "") +
                         " of " + std::to_string(width) + " x " + std::to_string(scene.image.height) + " at scale " +
                         std::to_string(scale) + " are " + count(total) + " supersampled pixels, above the limit of " +
                         count(kMaxScenePixels) + " for one scene (every frame is kept until the scene is written)");
}


std::vector<std::string> findSceneFiles(const std::string& goldenDir) {
    std::vector<std::string> files;
    std::error_code ec;
    for (const auto& demoDir : fs::directory_iterator(goldenDir, ec)) {
        if (!demoDir.is_directory()) continue;
        for (const auto& entry : fs::directory_iterator(demoDir.path(), ec))
            if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::string sceneId(const SceneCommon& scene) { return scene.demo + "/" + scene.name; }

}  // namespace cdlab::demos
