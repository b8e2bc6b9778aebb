#include "render/gif_writer.h"

#include <gif_lib.h>

#include <cstring>
#include <memory>
#include <mutex>

namespace cdlab::render {

namespace {

int appendBytes(GifFileType* gif, const GifByteType* data, int length) {
    auto* out = static_cast<std::string*>(gif->UserData);
    out->append(reinterpret_cast<const char*>(data), std::size_t(length));
    return length;
}

[[noreturn]] void fail(const std::string& what, int code) {
    const char* msg = GifErrorString(code);
    throw GifError("gif: " + what + ": " + (msg ? msg : "unknown giflib error"));
}

// giflib's GifQuantizeBuffer sorts with a comparator that reads a file-static variable (the axis
// being split): two threads quantising at once change each other's palettes (`cdlab figures` on
// workers gave a different animation.gif from run to run). One quantisation at a time.
std::mutex& quantizeMutex() {
    static std::mutex m;
    return m;
}

struct MapDeleter {
    void operator()(ColorMapObject* m) const { GifFreeMapObject(m); }
};

}  // namespace

std::string encodeGif(const std::vector<Image>& frames, const GifOptions& options) {
    if (frames.empty()) throw GifError("gif: no frames");
    const int w = frames[0].width, h = frames[0].height;
    if (w <= 0 || h <= 0 || w > 65535 || h > 65535) throw GifError("gif: frame size out of range");
    for (const Image& f : frames)
        if (f.width != w || f.height != h) throw GifError("gif: frames differ in size");

    std::string bytes;
    int error = 0;
    GifFileType* gif = EGifOpen(&bytes, appendBytes, &error);
    if (!gif) fail("open", error);
    // EGifCloseFile frees the handle even on error; make sure it runs exactly once.
    auto close = [&]() {
        int e = 0;
        GifFileType* g = gif;
        gif = nullptr;
        if (g && EGifCloseFile(g, &e) != GIF_OK) return e;
        return 0;
    };
    try {
        EGifSetGifVersion(gif, true);
        if (EGifPutScreenDesc(gif, w, h, 8, 0, nullptr) != GIF_OK) fail("screen descriptor", gif->Error);
        // Netscape 2.0 application extension: loop the animation.
        {
            unsigned char app[11];
            std::memcpy(app, "NETSCAPE2.0", 11);
            unsigned char loop[3] = {1, static_cast<unsigned char>(options.loopCount & 0xff),
                                     static_cast<unsigned char>((options.loopCount >> 8) & 0xff)};
            if (EGifPutExtensionLeader(gif, APPLICATION_EXT_FUNC_CODE) != GIF_OK ||
                EGifPutExtensionBlock(gif, 11, app) != GIF_OK || EGifPutExtensionBlock(gif, 3, loop) != GIF_OK ||
                EGifPutExtensionTrailer(gif) != GIF_OK)
                fail("loop extension", gif->Error);
        }
        const std::size_t n = std::size_t(w) * h;
        std::vector<GifByteType> red(n), green(n), blue(n), index(n);
        for (std::size_t k = 0; k < frames.size(); ++k) {
            const Image& f = frames[k];
            for (std::size_t i = 0; i < n; ++i) {
                red[i] = f.rgba[4 * i];
                green[i] = f.rgba[4 * i + 1];
                blue[i] = f.rgba[4 * i + 2];
            }
            std::unique_ptr<ColorMapObject, MapDeleter> map(GifMakeMapObject(256, nullptr));
            if (!map) throw GifError("gif: out of memory for a colour map");
            int colors = 256;
            int quantized;
            {
                const std::lock_guard<std::mutex> lock(quantizeMutex());
                quantized = GifQuantizeBuffer(unsigned(w), unsigned(h), &colors, red.data(), green.data(), blue.data(),
                                              index.data(), map->Colors);
            }
            if (quantized != GIF_OK) throw GifError("gif: colour quantisation failed");
            // Graphics control extension: frame delay, no transparency, disposal "do not dispose".
            const int delay = k + 1 == frames.size() ? options.lastDelayCentiseconds : options.delayCentiseconds;
            GraphicsControlBlock gcb{};
            gcb.DisposalMode = DISPOSE_DO_NOT;
            gcb.UserInputFlag = false;
            gcb.DelayTime = delay;
            gcb.TransparentColor = NO_TRANSPARENT_COLOR;
            GifByteType ext[4];
            EGifGCBToExtension(&gcb, ext);
            if (EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, 4, ext) != GIF_OK) fail("frame delay", gif->Error);
            if (EGifPutImageDesc(gif, 0, 0, w, h, false, map.get()) != GIF_OK) fail("image descriptor", gif->Error);
            for (int y = 0; y < h; ++y)
                if (EGifPutLine(gif, index.data() + std::size_t(y) * w, w) != GIF_OK) fail("pixels", gif->Error);
        }
    } catch (...) {
        close();
        throw;
    }
    if (int e = close()) fail("close", e);
    return bytes;
}

}  // namespace cdlab::render
