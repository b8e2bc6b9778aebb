// RGBA8 images and PNG I/O (stb_image / stb_image_write; exactly one TU, stb_impl.cpp,
// defines the implementations).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace cdlab::render {

/// Row-major RGBA8, first row = top of the picture.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  // width * height * 4 bytes

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(std::size_t(w) * h * 4, 0) {}
    std::uint8_t* pixel(int x, int y) { return &rgba[(std::size_t(y) * width + x) * 4]; }
    const std::uint8_t* pixel(int x, int y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
};

/// Thrown for unreadable / unwritable / malformed image files; what() is one line that names the file.
struct ImageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Decodes a PNG (any channel count, converted to RGBA8). Throws ImageError.
Image readPng(const std::string& path);

/// Encodes to PNG deterministically (no timestamps) and writes it atomically: to a temp file
/// in the same folder, then rename(), so an interrupted run never leaves a truncated PNG.
/// Creates missing parent folders. Throws ImageError (including write errors such as a full disk).
void writePngAtomic(const std::string& path, const Image& image);

/// Writes bytes atomically (temp file + rename); used for JSON/HTML outputs. Throws std::runtime_error.
void writeFileAtomic(const std::string& path, const std::string& bytes);

/// Box-filter downsample by an integer factor (supersampling resolve for --scale).
Image downsample(const Image& image, int factor);

/// Pastes src into dst with its top-left corner at (x, y), clipped.
void blit(Image& dst, const Image& src, int x, int y);

/// 64-bit FNV-1a of width, height and pixels: the exact-match fingerprint of decoded pixels.
std::uint64_t pixelHash(const Image& image);

}  // namespace cdlab::render
