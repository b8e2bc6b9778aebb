#include "app/harness/gallery.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>

#include "app/harness/scene_runner.h"
#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
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

namespace {

// Every page the gallery writes carries this line: what requireGalleryPage recognises as cdlab's.
const char* const kGenerator = "<meta name=\"generator\" content=\"cdlab figures\">";

struct GalleryScene {
    std::string demo, scene;  // plain names: the folder <out>/<demo>/<scene>/
    FigureManifest manifest;
    std::string id() const { return demo + "/" + scene; }
};

const char* const kGalleryStyle =
    "<style>body{font-family:sans-serif;margin:2em;color:#1a1a1f;max-width:1400px}"
    "h2{margin-top:1.6em;border-bottom:1px solid #ccc}"
    ".grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(300px,1fr));gap:1.2em}"
    ".card img{width:100%;border:1px solid #ccc}.card p{margin:0.3em 0;font-size:0.9em}"
    "figure{margin:2em 0}figure img{max-width:100%;border:1px solid #ccc}"
    "figcaption{font-size:1.05em;margin:0.4em 0}nav,.steps{margin:0.6em 0}nav a,.steps a{margin-right:1.2em}"
    "</style>";

// The frame that stands for a scene in the index: its result, else its contact sheet, else the first.
const FigureManifest::FrameEntry* keyFrame(const FigureManifest& m) {
    for (const char* name : {"result", "contact_sheet"})
        for (const auto& f : m.frames)
            if (f.name == name) return &f;
    return m.frames.empty() ? nullptr : &m.frames.front();
}

// <out>/<demo>/<scene>.html: every frame at full size in order, each with its caption, links to
// step through the frames and to the neighbouring scenes, and the scene's other files.
std::string scenePage(const GalleryScene& s, const GalleryScene* prev, const GalleryScene* next) {
    using render::htmlEscape;
    const FigureManifest& m = s.manifest;
    std::ostringstream h;
    const std::string title = m.title.empty() ? s.id() : m.title;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">" << kGenerator << "<title>"
      << htmlEscape(title) << "</title>\n" << kGalleryStyle << "</head><body>\n<nav><a href=\"../index.html\">all figures</a>";
    // Links apart by whitespace, so a narrow window wraps the line (issue 43: no break between
    // them, the index's demo line ran off a 1000-px window).
    if (prev) h << "\n<a href=\"../" << htmlEscape(prev->id()) << ".html\">&larr; " << htmlEscape(prev->id()) << "</a>";
    if (next) h << "\n<a href=\"../" << htmlEscape(next->id()) << ".html\">" << htmlEscape(next->id()) << " &rarr;</a>";
    h << "</nav>\n<h1>" << htmlEscape(title) << " <small>(" << htmlEscape(s.id()) << ")</small></h1>\n";
    if (!m.caption.empty()) h << "<p>" << htmlEscape(m.caption) << "</p>\n";
    h << "<p>";
    for (const std::string& f : m.files)
        if (f.size() < 4 || f.compare(f.size() - 4, 4, ".png") != 0)
            h << "<a href=\"" << htmlEscape(s.scene + "/" + f) << "\">" << htmlEscape(f) << "</a> ";
    h << "</p>\n";
    for (std::size_t i = 0; i < m.frames.size(); ++i) {
        const auto& f = m.frames[i];
        const std::string src = s.scene + "/" + f.name + ".png";
        h << "<figure id=\"" << htmlEscape(f.name) << "\"><figcaption><b>" << i + 1 << " / " << m.frames.size()
          << "</b> " << htmlEscape(f.caption) << "</figcaption>\n<div class=\"steps\">";
        if (i > 0) h << "<a href=\"#" << htmlEscape(m.frames[i - 1].name) << "\">&larr; previous</a>";
        if (i + 1 < m.frames.size()) h << "<a href=\"#" << htmlEscape(m.frames[i + 1].name) << "\">next &rarr;</a>";
        h << "<a href=\"" << htmlEscape(src) << "\">" << htmlEscape(f.name) << ".png</a>";
        h << "</div><a href=\"" << htmlEscape(src) << "\"><img src=\"" << htmlEscape(src) << "\" alt=\""
          << htmlEscape(f.caption) << "\"></a></figure>\n";
    }
    h << "</body></html>\n";
    return h.str();
}

}  // namespace

void requireGalleryPage(const std::string& page) {
    std::error_code ec;
    const fs::file_type type = fs::symlink_status(page, ec).type();
    if (type == fs::file_type::not_found) return;
    std::string head;
    if (type == fs::file_type::regular) {
        std::ifstream in(page, std::ios::binary);
        head.resize(4096);
        in.read(head.data(), std::streamsize(head.size()));
        head.resize(std::size_t(in.gcount()));
    }
    // Pages of earlier versions had no generator line; their style sheet is as distinctive.
    if (head.find(kGenerator) != std::string::npos || head.find(kGalleryStyle) != std::string::npos) return;
    throw InputError("refusing to overwrite " + printable(page) +
                     ": cdlab did not write it (not a cdlab gallery page); give --out a folder of its own");
}

int writeGallery(const std::string& outDir) {
    int refused = 0;
    const auto write = [&](const fs::path& page, const std::string& html) {
        try {
            requireGalleryPage(page.string());
            render::writeFileAtomic(page.string(), html);
        } catch (const InputError& e) {
            std::cerr << "cdlab figures: " << e.what() << "\n";
            ++refused;
        }
    };
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
    std::vector<GalleryScene> scenes;
    for (const auto& path : manifests) {
        try {
            scenes.push_back({path.parent_path().parent_path().filename().string(),
                              path.parent_path().filename().string(), readFigureManifest(path)});
        } catch (const InputError& e) {
            std::cerr << "cdlab figures: " << printable(e.what()) << " (left out of the gallery)\n";
        }
    }

    // One page per scene, <out>/<demo>/<scene>.html, with links to its neighbours.
    for (std::size_t i = 0; i < scenes.size(); ++i)
        write(fs::path(outDir) / (scenes[i].id() + ".html"),
              scenePage(scenes[i], i > 0 ? &scenes[i - 1] : nullptr, i + 1 < scenes.size() ? &scenes[i + 1] : nullptr));

    // The index: by demo, a grid of each scene's key frame linking to its page.
    using render::htmlEscape;
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">" << kGenerator
      << "<title>cdlab figures</title>\n"
      << kGalleryStyle << "</head><body>\n<h1>cdlab figures</h1>\n<nav>";
    std::vector<std::string> demos;
    for (const GalleryScene& s : scenes)
        if (demos.empty() || demos.back() != s.demo) demos.push_back(s.demo);
    for (const std::string& d : demos) h << "\n<a href=\"#" << htmlEscape(d) << "\">" << htmlEscape(d) << "</a>";
    h << "</nav>\n";
    for (const std::string& d : demos) {
        h << "<section id=\"" << htmlEscape(d) << "\"><h2>" << htmlEscape(d) << "</h2><div class=\"grid\">\n";
        for (const GalleryScene& s : scenes) {
            if (s.demo != d) continue;
            const std::string page = s.id() + ".html";
            const auto* key = keyFrame(s.manifest);
            h << "<div class=\"card\" id=\"" << htmlEscape(s.id()) << "\"><a href=\"" << htmlEscape(page) << "\">";
            if (key)
                h << "<img src=\"" << htmlEscape(s.id() + "/" + key->name + ".png") << "\" alt=\""
                  << htmlEscape(key->caption) << "\">";
            h << "</a><p><a href=\"" << htmlEscape(page) << "\"><b>"
              << htmlEscape(s.manifest.title.empty() ? s.scene : s.manifest.title) << "</b></a> ("
              << s.manifest.frames.size() << " frame" << (s.manifest.frames.size() == 1 ? "" : "s") << ")</p></div>\n";
        }
        h << "</div></section>\n";
    }
    h << "</body></html>\n";
    write(fs::path(outDir) / "index.html", h.str());
    return refused;
}

}  // namespace cdlab::demos
