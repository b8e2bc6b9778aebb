// The static figure gallery: out/figures/index.html, one section per scene with its frames and
// captions, relative image links only (opens offline, no scripts).
#pragma once

#include <string>

namespace cdlab::demos {

/// Scans <outDir>/<demo>/<scene>/manifest.json and writes <outDir>/index.html atomically.
void writeGallery(const std::string& outDir);

}  // namespace cdlab::demos
