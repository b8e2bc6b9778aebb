// The static figure gallery, a place to pick slides from: out/figures/index.html, a grid by demo
// of each scene's key frame (its result, else its contact sheet), each linking to the scene's own
// page out/figures/<demo>/<scene>.html with every frame at full size in order, its caption,
// previous / next links to step through the frames and the scenes, and links to the PNGs, GIF and
// trace; relative links only (opens offline, no scripts). Also the per-scene manifest that
// `cdlab figures` writes and the gallery reads.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// <out>/<demo>/<scene>/manifest.json: the cache key and what a figures run wrote into the folder.
/// `files` is the only list of files cdlab may later delete there.
struct FigureManifest {
    struct FrameEntry {
        std::string name;  // file stem of <name>.png
        std::string caption;
        Json layout;  // the frame's text and markers (layoutJson); null when not recorded
    };
    std::string key;  // cache key (scene bytes, options, executable)
    std::string title, caption;
    std::vector<FrameEntry> frames;
    std::vector<std::string> files;  // every file written: plain names (no '/', not "..")
};

/// Reads a manifest written by `cdlab figures`. Anything else — not JSON, another layout, a file
/// name that could leave the folder — throws InputError naming the file and the JSON path.
FigureManifest readFigureManifest(const std::filesystem::path& file);
/// The manifest's JSON text (readFigureManifest reads it back).
std::string figureManifestText(const FigureManifest& manifest);

/// Scans <outDir>/<demo>/<scene>/manifest.json and writes <outDir>/index.html and the scene pages
/// <outDir>/<demo>/<scene>.html atomically. A manifest that does not read is reported on stderr
/// with its path and left out of the page. A page whose path holds a file cdlab did not write
/// (requireGalleryPage) is not replaced: reported on stderr and counted in the result.
int writeGallery(const std::string& outDir);

/// Throws InputError when `page` exists and is not a gallery page cdlab wrote (the user's own
/// index.html in --out; hostile_harness_test "figures --out keeps the user's index.html").
void requireGalleryPage(const std::string& page);

}  // namespace cdlab::demos
