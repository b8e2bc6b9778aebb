#include "demos/lib/scene.h"

#include <algorithm>
#include <filesystem>

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
            cx = center->at(0).asNumber();
            cy = center->at(1).asNumber();
        }
        cam = render::Camera::twoD(cx, cy, r.get("height").asPositive());
    } else {
        cam.projection = projection == "perspective" ? render::Camera::Projection::Perspective
                                                     : render::Camera::Projection::Orthographic;
        if (auto n = r.find("eye")) cam.eye = n->asVec3();
        if (auto n = r.find("target")) cam.target = n->asVec3();
        if (auto n = r.find("up")) cam.up = n->asVec3();
        if (auto n = r.find("fov")) cam.fovYDegrees = n->asPositive();
        if (auto n = r.find("height")) cam.viewHeight = n->asPositive();
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
    s.name = fs::path(file).stem().string();
    s.demo = r.get("demo").asString();
    s.title = r.stringOr("title", s.name);
    s.caption = r.stringOr("caption", "");
    r.ignore("_comment");
    if (auto image = r.find("image")) {
        ObjectReader ir(*image);
        s.image.width = ir.find("width") ? ir.get("width").asInt(16, 8192) : s.image.width;
        s.image.height = ir.find("height") ? ir.get("height").asInt(16, 8192) : s.image.height;
        s.image.scale = ir.find("scale") ? ir.get("scale").asInt(1, 4) : s.image.scale;
        ir.finish();
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
