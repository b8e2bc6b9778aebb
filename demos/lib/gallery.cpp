#include "demos/lib/gallery.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "demos/lib/json_reader.h"
#include "render/compare.h"
#include "render/image.h"

namespace cdlab::demos {

namespace fs = std::filesystem;

void writeGallery(const std::string& outDir) {
    std::vector<fs::path> manifests;
    std::error_code ec;
    for (const auto& demo : fs::directory_iterator(outDir, ec))
        if (demo.is_directory())
            for (const auto& scene : fs::directory_iterator(demo.path(), ec))
                if (fs::exists(scene.path() / "manifest.json")) manifests.push_back(scene.path() / "manifest.json");
    std::sort(manifests.begin(), manifests.end());

    using render::htmlEscape;
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>cdlab figures</title>\n"
         "<style>body{font-family:sans-serif;margin:2em;color:#1a1a1f}h2{margin-top:2em}"
         "figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top}"
         "img{max-width:360px;border:1px solid #ccc}figcaption{max-width:360px;font-size:0.85em}"
         "nav a{margin-right:1em}</style></head><body>\n<h1>cdlab figures</h1>\n<nav>";
    std::vector<std::pair<std::string, Json>> scenes;
    for (const auto& m : manifests) {
        std::ifstream in(m);
        std::ostringstream ss;
        ss << in.rdbuf();
        Json j = Json::parse(ss.str(), nullptr, false);
        if (j.is_discarded()) continue;
        std::string id = m.parent_path().parent_path().filename().string() + "/" + m.parent_path().filename().string();
        scenes.emplace_back(id, j);
        h << "<a href=\"#" << htmlEscape(id) << "\">" << htmlEscape(id) << "</a>\n";
    }
    h << "</nav>\n";
    for (const auto& [id, j] : scenes) {
        h << "<section id=\"" << htmlEscape(id) << "\"><h2>" << htmlEscape(j.value("title", id)) << " <small>("
          << htmlEscape(id) << ")</small></h2>\n";
        if (!j.value("caption", "").empty()) h << "<p>" << htmlEscape(j.value("caption", "")) << "</p>\n";
        for (const auto& f : j.value("frames", Json::array())) {
            std::string src = id + "/" + f.value("name", "") + ".png";
            h << "<figure><a href=\"" << htmlEscape(src) << "\"><img src=\"" << htmlEscape(src) << "\" alt=\""
              << htmlEscape(f.value("caption", "")) << "\"></a><figcaption>" << htmlEscape(f.value("caption", ""))
              << "</figcaption></figure>\n";
        }
        for (const auto& f : j.value("files", Json::array()))
            if (f.get<std::string>() != "trace.json" && f.get<std::string>().find(".png") == std::string::npos)
                h << "<p><a href=\"" << htmlEscape(id + "/" + f.get<std::string>()) << "\">" << htmlEscape(f.get<std::string>())
                  << "</a></p>\n";
        h << "<p><a href=\"" << htmlEscape(id) << "/trace.json\">trace.json</a></p></section>\n";
    }
    h << "</body></html>\n";
    render::writeFileAtomic((fs::path(outDir) / "index.html").string(), h.str());
}

}  // namespace cdlab::demos
