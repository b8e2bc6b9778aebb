#include "demos/harness/gallery.h"

#include <algorithm>
#include <iostream>
#include <sstream>

#include "demos/harness/scene_runner.h"
#include "demos/scene/json_reader.h"
#include "demos/scene/scene.h"
#include "render/compare.h"
#include "render/image.h"

namespace cdlab::demos {

namespace fs = std::filesystem;

namespace {

std::string plainFileName(const JsonNode& node) {
    std::string name = node.asString();
    if (!isPlainName(name) || name == "manifest.json") node.fail("not a plain file name in the scene folder: " + name);
    return name;
}

}  // namespace

FigureManifest readFigureManifest(const fs::path& file) {
    const Json json = readJsonFile(file.string());
    ObjectReader r(JsonNode(json, "$", file.string()));
    FigureManifest m;
    m.key = r.get("key").asString();
    m.title = r.get("title").asString();
    m.caption = r.get("caption").asString();
    for (const JsonNode& f : r.get("frames").items()) {
        ObjectReader fr(f);
        std::string name = plainFileName(fr.get("name"));
        m.frames.push_back({name, fr.get("caption").asString(), fr.find("layout") ? fr.get("layout").raw() : Json()});
        fr.finish();
    }
    for (const JsonNode& f : r.get("files").items()) m.files.push_back(plainFileName(f));
    r.finish();
    return m;
}

std::string figureManifestText(const FigureManifest& m) {
    Json j = {
        {"key", m.key}, {"title", m.title}, {"caption", m.caption}, {"frames", Json::array()}, {"files", m.files}};
    for (const auto& f : m.frames) {
        Json entry = {{"name", f.name}, {"caption", f.caption}};
        if (!f.layout.is_null()) entry["layout"] = f.layout;
        j["frames"].push_back(std::move(entry));
    }
    return j.dump(1) + "\n";
}

void writeGallery(const std::string& outDir) {
    // Only <plain demo>/<plain scene> folders can be cdlab's; anything else in out/ is not read.
    std::vector<fs::path> manifests;
    std::error_code ec;
    for (const auto& demo : fs::directory_iterator(outDir, ec)) {
        if (!demo.is_directory(ec) || !isPlainName(demo.path().filename().string())) continue;
        for (const auto& scene : fs::directory_iterator(demo.path(), ec))
            if (isPlainName(scene.path().filename().string()) &&
                fs::symlink_status(scene.path() / "manifest.json", ec).type() != fs::file_type::not_found)
                manifests.push_back(scene.path() / "manifest.json");
    }
    std::sort(manifests.begin(), manifests.end());

    using render::htmlEscape;
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>cdlab figures</title>\n"
         "<style>body{font-family:sans-serif;margin:2em;color:#1a1a1f}h2{margin-top:2em}"
         "figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top}"
         "img{max-width:360px;border:1px solid #ccc}figcaption{max-width:360px;font-size:0.85em}"
         "nav a{margin-right:1em}</style></head><body>\n<h1>cdlab figures</h1>\n<nav>";
    std::vector<std::pair<std::string, FigureManifest>> scenes;
    for (const auto& path : manifests) {
        try {
            FigureManifest m = readFigureManifest(path);
            std::string id =
                path.parent_path().parent_path().filename().string() + "/" + path.parent_path().filename().string();
            h << "<a href=\"#" << htmlEscape(id) << "\">" << htmlEscape(id) << "</a>\n";
            scenes.emplace_back(std::move(id), std::move(m));
        } catch (const InputError& e) {
            std::cerr << "cdlab figures: " << e.what() << " (left out of the gallery)\n";
        }
    }
    h << "</nav>\n";
    for (const auto& [id, m] : scenes) {
        h << "<section id=\"" << htmlEscape(id) << "\"><h2>" << htmlEscape(m.title.empty() ? id : m.title)
          << " <small>(" << htmlEscape(id) << ")</small></h2>\n";
        if (!m.caption.empty()) h << "<p>" << htmlEscape(m.caption) << "</p>\n";
        for (const auto& f : m.frames) {
            std::string src = id + "/" + f.name + ".png";
            h << "<figure><a href=\"" << htmlEscape(src) << "\"><img src=\"" << htmlEscape(src) << "\" alt=\""
              << htmlEscape(f.caption) << "\"></a><figcaption>" << htmlEscape(f.caption) << "</figcaption></figure>\n";
        }
        for (const auto& f : m.files)
            if (f != "trace.json" && f.find(".png") == std::string::npos)
                h << "<p><a href=\"" << htmlEscape(id + "/" + f) << "\">" << htmlEscape(f) << "</a></p>\n";
        h << "<p><a href=\"" << htmlEscape(id) << "/trace.json\">trace.json</a></p></section>\n";
    }
    h << "</body></html>\n";
    render::writeFileAtomic((fs::path(outDir) / "index.html").string(), h.str());
}

}  // namespace cdlab::demos
