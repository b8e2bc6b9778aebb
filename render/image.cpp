#include "render/image.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_image.h>
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace cdlab::render {

namespace {

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

template <class Error>
[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw Error("cannot write '" + path + "': " + what);
}

/// Temp file in the target folder + write + fsync + rename (POSIX rename is atomic within a
/// file system, so readers see the old file or the complete new one, never a truncated one).
template <class Error>
void writeAtomic(const std::string& path, const void* data, std::size_t size) {
    namespace fs = std::filesystem;
    if (path.empty()) throw Error("cannot write '': empty path");
    const fs::path target(path);
    std::error_code ec;
    if (target.has_parent_path()) {
        fs::create_directories(target.parent_path(), ec);
        if (ec) fail<Error>(path, "cannot create folder '" + target.parent_path().string() + "': " + ec.message());
    }
    // Unique per process and call, so parallel writers of the same file never share a temp file.
    static std::atomic<unsigned> counter{0};
    const std::string temp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) fail<Error>(path, std::strerror(errno));
    auto abandon = [&](int err) {
        ::close(fd);
        ::unlink(temp.c_str());
        fail<Error>(path, std::strerror(err));
    };
    const auto* bytes = static_cast<const unsigned char*>(data);
    std::size_t done = 0;
    while (done < size) {
        const ssize_t n = ::write(fd, bytes + done, size - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) abandon(n < 0 ? errno : ENOSPC);  // 0 bytes written: treat as a full disk
        done += std::size_t(n);
    }
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) abandon(errno);  // EINVAL: fs without fsync
    if (::close(fd) != 0) {
        const int err = errno;
        ::unlink(temp.c_str());
        fail<Error>(path, std::strerror(err));
    }
    if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(temp.c_str());
        fail<Error>(path, std::strerror(err));
    }
}

void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* p = static_cast<const unsigned char*>(data);
    out->insert(out->end(), p, p + size);
}

}  // namespace

Image readPng(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ImageError("cannot read '" + path + "': " + std::strerror(errno));
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw ImageError("cannot read '" + path + "': read error");
    if (bytes.empty()) throw ImageError("cannot decode '" + path + "': empty file, not a PNG");
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kPngSignature, 8) != 0)
        throw ImageError("cannot decode '" + path + "': not a PNG (bad signature)");
    if (bytes.size() > std::size_t(INT32_MAX)) throw ImageError("cannot decode '" + path + "': file too large");
    int w = 0, h = 0, channels = 0;
    stbi_uc* pixels = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels, 4);
    if (!pixels) {
        const std::string reason = stbi_failure_reason() ? stbi_failure_reason() : "unknown";
        // stb's terse reasons: "outofdata"/"bad zlib"/"no IEND"... mostly mean a cut-off file.
        throw ImageError("cannot decode '" + path + "': corrupt or truncated PNG (" + std::to_string(bytes.size()) +
                         " bytes; stb_image: " + reason + ")");
    }
    Image image(w, h);
    std::memcpy(image.rgba.data(), pixels, image.rgba.size());
    stbi_image_free(pixels);
    return image;
}

void writePngAtomic(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw ImageError("cannot write '" + path + "': invalid image " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " with " + std::to_string(image.rgba.size()) + " bytes");
    // stb_image_write writes no time or text chunks: same pixels -> same bytes. The encoder
    // settings are globals; they are set to their defaults explicitly so nobody else's
    // tweak changes our files.
    stbi_write_png_compression_level = 8;
    stbi_write_force_png_filter = -1;
    std::vector<unsigned char> png;
    png.reserve(image.rgba.size() / 4);
    if (!stbi_write_png_to_func(appendBytes, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4))
        throw ImageError("cannot write '" + path + "': PNG encoding failed");
    writeAtomic<ImageError>(path, png.data(), png.size());
}

void writeFileAtomic(const std::string& path, const std::string& bytes) {
    writeAtomic<std::runtime_error>(path, bytes.data(), bytes.size());
}

Image downsample(const Image& image, int factor) {
    if (factor <= 1) return image;
    const int w = image.width / factor, h = image.height / factor;  // a partial last block is dropped
    Image out(w, h);
    const int n = factor * factor;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            unsigned sum[4] = {0, 0, 0, 0};
            for (int dy = 0; dy < factor; ++dy)
                for (int dx = 0; dx < factor; ++dx) {
                    const std::uint8_t* p = image.pixel(x * factor + dx, y * factor + dy);
                    for (int c = 0; c < 4; ++c) sum[c] += p[c];
                }
            std::uint8_t* q = out.pixel(x, y);
            for (int c = 0; c < 4; ++c) q[c] = std::uint8_t((sum[c] + unsigned(n) / 2) / unsigned(n));  // round to nearest
        }
    return out;
}

void blit(Image& dst, const Image& src, int x, int y) {
    const int x0 = std::max(0, x), y0 = std::max(0, y);
    const int x1 = std::min(dst.width, x + src.width), y1 = std::min(dst.height, y + src.height);
    if (x0 >= x1) return;
    for (int row = y0; row < y1; ++row)
        std::memcpy(dst.pixel(x0, row), src.pixel(x0 - x, row - y), std::size_t(x1 - x0) * 4);
}

std::uint64_t pixelHash(const Image& image) {
    // FNV-1a 64 (Fowler, Noll, Vo): offset basis and prime from the reference.
    std::uint64_t h = 14695981039346656037ull;
    auto mix = [&h](std::uint8_t byte) {
        h ^= byte;
        h *= 1099511628211ull;
    };
    for (int v : {image.width, image.height})
        for (int i = 0; i < 4; ++i) mix(std::uint8_t(std::uint32_t(v) >> (8 * i)));
    for (std::uint8_t b : image.rgba) mix(b);
    return h;
}

}  // namespace cdlab::render
