// Animated GIF encoding with giflib (GIF89a, Netscape looping extension). Each frame is
// quantised to its own 256-colour local palette with giflib's GifQuantizeBuffer (median cut on
// 5-bit-per-channel colours, Heckbert 1982), which is deterministic: the same pixels give the same
// bytes, on any number of threads (the quantisation, which keeps state in giflib, runs one at a
// time). Knows nothing about what the frames show.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "render/image.h"

namespace cdlab::render {

struct GifOptions {
    int delayCentiseconds = 120;      ///< display time of each frame (1/100 s)
    int lastDelayCentiseconds = 300;  ///< display time of the last frame (a pause before looping)
    int loopCount = 0;                ///< Netscape loop count, 0 = forever
};

/// Thrown for empty input, frames of different sizes or a giflib error; what() is one line.
struct GifError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Encodes RGBA8 frames (alpha ignored; all frames the same size) into GIF file bytes.
std::string encodeGif(const std::vector<Image>& frames, const GifOptions& options = {});

}  // namespace cdlab::render
