// RGBA8 images and PNG I/O (decoding: stb_image, its one implementation TU is stb_impl.cpp;
// encoding: libpng at its fast setting).
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/color.h"
#include "render/figure_layout.h"

namespace cdlab::render {

/// Row-major RGBA8, first row = top of the picture.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  // width * height * 4 bytes
    FigureLayout layout;             // where its text and markers are, in its pixels (empty for a decoded PNG)
    /// Pixels per layout unit: a figure drawn at `--scale 2` (a print figure) has twice the pixels
    /// of the same figure at scale 1 in each direction; the code that composes it places panels in
    /// layout units (blit, paintRect), the same at every scale.
    int scale = 1;

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(std::size_t(w) * h * 4, 0) {}
    /// A blank w x h picture in layout units: (w * scale) x (h * scale) pixels.
    static Image blank(int w, int h, int scale) {
        Image im(w * scale, h * scale);
        im.scale = scale;
        return im;
    }
    std::uint8_t* pixel(int x, int y) { return &rgba[(std::size_t(y) * width + x) * 4]; }
    const std::uint8_t* pixel(int x, int y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
};

/// Thrown for unreadable / unwritable / malformed image files; what() is one line that names the file.
struct ImageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Largest PNG file readPng reads: the size of an incompressible 8192 x 8192 RGBA image (the
/// largest frame a scene can ask for) ...
constexpr std::size_t kMaxPngFileBytes = std::size_t(256) << 20;
/// ... and the most pixels it decodes (checked in the header, before stb_image allocates them).
constexpr std::int64_t kMaxPngPixels = std::int64_t(8192) * 8192;

/// Decodes a PNG (any channel count, converted to RGBA8). Throws ImageError naming the file: missing,
/// a directory, larger than kMaxPngFileBytes / kMaxPngPixels, not a PNG, corrupt.
Image readPng(const std::string& path);

/// Reads a whole file of at most `maxBytes` into `bytes`. Refuses a directory; reads at most
/// maxBytes + 1 bytes, so /dev/zero or an endless FIFO costs no more than the limit. On failure
/// returns false with `problem` set to a phrase without the path: "cannot open: <reason>", "is a
/// directory, not a file", "larger than the 16 MiB limit for <kind>", "read error: <reason>".
bool readFileBounded(const std::string& path, std::size_t maxBytes, const std::string& kind, std::string& bytes,
                     std::string& problem);

/// Encodes to PNG deterministically (no timestamps) and writes it atomically: to a temp file
/// in the same folder, then rename(), so an interrupted run never leaves a truncated PNG.
/// Creates missing parent folders. Throws ImageError (including write errors such as a full disk).
void writePngAtomic(const std::string& path, const Image& image);

/// Writes bytes atomically (temp file + rename); used for JSON/HTML outputs. Throws std::runtime_error.
void writeFileAtomic(const std::string& path, const std::string& bytes);

/// SIGINT, SIGTERM and SIGHUP (where their action is still the default) first remove the temp
/// files of the atomic writes in flight, then end the process as the signal would have
/// (hostile_harness_test "an interrupted render leaves no temp file"). For commands that write.
void removeTempFilesOnSignal();

/// Removes the temp files "<name>.tmp.<pid>.<n>" in `dir` (not below it) whose <name> is one of
/// `names` (the files cdlab writes there) and whose process is gone: what a run killed by SIGKILL
/// or a power cut left. Files of running processes, this one's included, and every other name
/// ("data.csv.tmp.5.1" of the user's) are kept.
void removeStaleTempFiles(const std::string& dir, const std::vector<std::string>& names);

/// Writes several files as one unit (a scene's frames, trace and manifest): each add*() stages a
/// file (a temp file with a name unique to this process and call, written and fsynced); commit()
/// renames them all into place, in the order added. A failure while staging, or destruction
/// without commit(), removes the temp files: every target keeps its previous content.
class FileSetWriter {
public:
    FileSetWriter() = default;
    FileSetWriter(const FileSetWriter&) = delete;
    FileSetWriter& operator=(const FileSetWriter&) = delete;
    ~FileSetWriter();
    void addPng(const std::string& path, const Image& image);         // throws ImageError
    void addFile(const std::string& path, const std::string& bytes);  // throws std::runtime_error
    /// Throws std::runtime_error naming the file whose rename failed (earlier ones are in place).
    void commit();

private:
    struct Staged {
        std::string temp, target;
        int slot;  // the temp file's entry in the signal handler's table, or -1
    };
    void keep(const std::string& temp, const std::string& target, int slot);  // or remove it and throw
    std::vector<Staged> staged_;
};

/// Box-filter downsample by an integer factor (a supersampling resolve, a contact sheet's
/// thumbnail); the layout shrinks with it; the scale is kept (the thumbnail of a 2x frame goes
/// into a 2x sheet).
Image downsample(const Image& image, int factor);

/// Pastes src into dst with its top-left corner at (x, y) in dst's layout units (pixels times
/// dst.scale), clipped; src's layout joins dst's.
void blit(Image& dst, const Image& src, int x, int y);

/// `top` over `bottom`, left-aligned, in a picture as wide as the wider one (the rest transparent black).
Image stackVertically(const Image& top, const Image& bottom);

/// Paints the w x h rectangle whose top-left corner is (x, y), in layout units (times image.scale),
/// in `color` (channels clamped to 0..1, opaque), clipped: the rules drawn between panels once
/// they are blitted into a page.
void paintRect(Image& image, int x, int y, int w, int h, const Color& color);

/// 64-bit FNV-1a of width, height and pixels: the exact-match fingerprint of decoded pixels.
std::uint64_t pixelHash(const Image& image);

}  // namespace cdlab::render
