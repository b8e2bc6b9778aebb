#include "render/image.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_image.h>
#pragma GCC diagnostic pop
#include <png.h>

namespace cdlab::render {

namespace {

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

// ---- Temp files in flight, for the signal handler -----------------------------------------------
// A fixed table (no allocation, no lock: a signal handler may read it at any moment, on any
// thread, while other threads go on). A slot's word is (generation << 2) | state, state free (0),
// being filled (1) or naming a temp file that exists or is about to (2); every fill raises the
// generation, so the handler, which copies a live path and then reads the word again, unlinks
// only a path no other thread changed under it (a seqlock). More temp files in flight than slots
// go untracked, as does one another thread opens between the handler's sweep and the end of the
// process; removeStaleTempFiles finds those on a later run.
constexpr int kTempSlots = 256;
constexpr std::size_t kTempPathBytes = 4096;
struct TempSlot {
    std::atomic<std::uint64_t> word{0};
    char path[kTempPathBytes];
};
TempSlot g_temps[kTempSlots];
static_assert(std::atomic<std::uint64_t>::is_always_lock_free, "the signal handler reads the slots' words");

int trackTemp(const std::string& temp) {
    if (temp.size() >= kTempPathBytes) return -1;
    for (int i = 0; i < kTempSlots; ++i) {
        std::uint64_t word = g_temps[i].word.load();
        if ((word & 3) != 0 || !g_temps[i].word.compare_exchange_strong(word, word | 1)) continue;
        std::memcpy(g_temps[i].path, temp.c_str(), temp.size() + 1);
        g_temps[i].word.store(((word >> 2) + 1) << 2 | 2);
        return i;
    }
    return -1;
}

void untrackTemp(int slot) {
    if (slot >= 0) g_temps[slot].word.store(g_temps[slot].word.load() & ~std::uint64_t(3));
}

extern "C" void removeTempsAndResignal(int sig) {
    const int savedErrno = errno;
    char path[kTempPathBytes];
    for (TempSlot& t : g_temps) {
        const std::uint64_t before = t.word.load();
        if ((before & 3) != 2) continue;
        std::size_t n = 0;
        while (n + 1 < kTempPathBytes && t.path[n] != '\0') path[n] = t.path[n], ++n;
        path[n] = '\0';
        if (t.word.load() == before) ::unlink(path);  // the copy is the path of this generation
    }
    ::signal(sig, SIG_DFL);
    ::raise(sig);  // delivered when the handler returns: the process ends as the signal asks
    errno = savedErrno;
}

template <class Error>
[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw Error("cannot write '" + path + "': " + what);
}

struct StagedTemp {
    std::string temp;
    int slot;  // in g_temps, or -1
};

/// Writes `data` to a new temp file in the target's folder and fsyncs it; returns the temp name
/// and its slot in the signal handler's table (the caller untracks it once renamed or removed).
/// The name is unique per process and call, so parallel writers of one file (two runs into the
/// same folder) never share a temp file. On failure the temp file is removed.
template <class Error>
StagedTemp stageFile(const std::string& path, const void* data, std::size_t size) {
    namespace fs = std::filesystem;
    if (path.empty()) throw Error("cannot write '': empty path");
    const fs::path target(path);
    std::error_code ec;
    if (target.has_parent_path()) {
        fs::create_directories(target.parent_path(), ec);
        if (ec) fail<Error>(path, "cannot create folder '" + target.parent_path().string() + "': " + ec.message());
    }
    // Found now, not at the rename: a FileSetWriter then fails before any file of its set is replaced.
    if (fs::symlink_status(target, ec).type() == fs::file_type::directory) fail<Error>(path, "is a directory");
    static std::atomic<unsigned> counter{0};
    const std::string temp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    const int slot = trackTemp(temp);  // before the file exists
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int err = errno;
        untrackTemp(slot);
        fail<Error>(path, std::strerror(err));
    }
    auto abandon = [&](int err) {
        ::close(fd);
        ::unlink(temp.c_str());
        untrackTemp(slot);
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
        untrackTemp(slot);
        fail<Error>(path, std::strerror(err));
    }
    return {temp, slot};
}

/// POSIX rename is atomic within a file system: readers see the old file or the complete new one.
template <class Error>
void commitFile(const StagedTemp& staged, const std::string& path) {
    if (::rename(staged.temp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(staged.temp.c_str());
        untrackTemp(staged.slot);
        fail<Error>(path, std::strerror(err));
    }
    untrackTemp(staged.slot);
}

/// Temp file in the target folder + write + fsync + rename: never a truncated target.
template <class Error>
void writeAtomic(const std::string& path, const void* data, std::size_t size) {
    commitFile<Error>(stageFile<Error>(path, data, size), path);
}

std::string sizeText(std::size_t bytes) {
    if (bytes % (std::size_t(1) << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes) + " bytes";
}

}  // namespace

void removeTempFilesOnSignal() {
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction old {};
        if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;  // e.g. nohup: kept
        struct sigaction action {};
        action.sa_handler = removeTempsAndResignal;
        sigemptyset(&action.sa_mask);
        ::sigaction(sig, &action, nullptr);
    }
}

void removeStaleTempFiles(const std::string& dir, const std::vector<std::string>& names) {
    namespace fs = std::filesystem;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        // <name>.tmp.<pid>.<n>: digits after the last two dots, ".tmp" before them.
        const std::size_t last = name.rfind('.');
        if (last == std::string::npos || last == 0) continue;
        const std::size_t pidDot = name.rfind('.', last - 1);
        if (pidDot == std::string::npos || pidDot < 5 || name.compare(pidDot - 4, 4, ".tmp") != 0) continue;
        if (std::find(names.begin(), names.end(), name.substr(0, pidDot - 4)) == names.end()) continue;
        const std::string pidText = name.substr(pidDot + 1, last - pidDot - 1), n = name.substr(last + 1);
        const auto digits = [](const std::string& t) {
            return !t.empty() && t.size() <= 10 && std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
        };
        if (!digits(pidText) || !digits(n)) continue;
        const long pid = std::stol(pidText);
        if (pid <= 0 || pid > std::numeric_limits<pid_t>::max() || pid == ::getpid()) continue;
        if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to ask
        if (fs::symlink_status(it->path(), ec).type() == fs::file_type::regular) fs::remove(it->path(), ec);
        ec.clear();
    }
}

bool readFileBounded(const std::string& path, std::size_t maxBytes, const std::string& kind, std::string& bytes,
                     std::string& problem) {
    bytes.clear();
    // O_NONBLOCK is not used: a FIFO (`<(cat scene.json)`) waits for its writer, as cat would.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        problem = std::string("cannot open: ") + std::strerror(errno);
        return false;
    }
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
        ::close(fd);
        problem = "is a directory, not a file";
        return false;
    }
    if (S_ISREG(st.st_mode) && std::uintmax_t(st.st_size) > maxBytes) {  // refused before reading
        ::close(fd);
        problem = "larger than the " + sizeText(maxBytes) + " limit for " + kind;
        return false;
    }
    // Devices and pipes have no size: read at most one byte past the limit.
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            problem = std::string("read error: ") + std::strerror(errno);
            ::close(fd);
            bytes.clear();
            return false;
        }
        if (n == 0) break;
        if (bytes.size() + std::size_t(n) > maxBytes) {
            ::close(fd);
            bytes.clear();
            problem = "larger than the " + sizeText(maxBytes) + " limit for " + kind;
            return false;
        }
        bytes.append(buffer, std::size_t(n));
    }
    ::close(fd);
    return true;
}

Image readPng(const std::string& path) {
    std::string bytes, problem;
    if (!readFileBounded(path, kMaxPngFileBytes, "a PNG file", bytes, problem))
        throw ImageError("cannot read '" + path + "': " + problem);
    if (bytes.empty()) throw ImageError("cannot decode '" + path + "': empty file, not a PNG");
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kPngSignature, 8) != 0)
        throw ImageError("cannot decode '" + path + "': not a PNG (bad signature)");
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    int w = 0, h = 0, channels = 0;
    // The header's size is checked before stb_image allocates w * h * 4 bytes for it.
    if (stbi_info_from_memory(data, int(bytes.size()), &w, &h, &channels) &&
        std::int64_t(w) * std::int64_t(h) > kMaxPngPixels)
        throw ImageError("cannot decode '" + path + "': " + std::to_string(w) + " x " + std::to_string(h) +
                         " pixels, more than the limit of " + std::to_string(kMaxPngPixels) + " (8192 x 8192)");
    stbi_uc* pixels = stbi_load_from_memory(data, int(bytes.size()), &w, &h, &channels, 4);
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

namespace {

std::vector<unsigned char> encodePng(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0 || image.rgba.size() != std::size_t(image.width) * image.height * 4)
        throw ImageError("cannot write '" + path + "': invalid image " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " with " + std::to_string(image.rgba.size()) + " bytes");
    // libpng's simplified writer at its fast setting (PNG_IMAGE_FLAG_FAST: quick filters, a low zlib
    // level): ~6x faster than stb_image_write's own deflate on a 1024x1024 frame, files somewhat
    // larger. No time or text chunks: same pixels -> same bytes. Goldens compare decoded pixels.
    png_image info{};
    info.version = PNG_IMAGE_VERSION;
    info.width = static_cast<png_uint_32>(image.width);
    info.height = static_cast<png_uint_32>(image.height);
    info.format = PNG_FORMAT_RGBA;
    info.flags = PNG_IMAGE_FLAG_FAST;
    const png_int_32 stride = image.width * 4;
    // One encoding into a buffer of libpng's upper bound (asking for the size first with a null
    // buffer runs the whole encoder twice: it was half of `--profile`'s PNG time).
    png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(info);
    const std::unique_ptr<unsigned char[]> buffer(new unsigned char[size]);  // uninitialised: written below
    if (!png_image_write_to_memory(&info, buffer.get(), &size, 0, image.rgba.data(), stride, nullptr))
        throw ImageError("cannot write '" + path + "': PNG encoding failed (" + info.message + ")");
    std::vector<unsigned char> png(buffer.get(), buffer.get() + size);
    return png;
}

}  // namespace

void writePngAtomic(const std::string& path, const Image& image) {
    const std::vector<unsigned char> png = encodePng(path, image);
    writeAtomic<ImageError>(path, png.data(), png.size());
}

void writeFileAtomic(const std::string& path, const std::string& bytes) {
    writeAtomic<std::runtime_error>(path, bytes.data(), bytes.size());
}

void FileSetWriter::keep(const std::string& temp, const std::string& target, int slot) {
    try {
        staged_.push_back({temp, target, slot});
    } catch (...) {  // out of memory: the staged file goes, as a failed staging's would
        ::unlink(temp.c_str());
        untrackTemp(slot);
        throw;
    }
}

FileSetWriter::~FileSetWriter() {
    for (const Staged& s : staged_) {
        ::unlink(s.temp.c_str());
        untrackTemp(s.slot);
    }
}

void FileSetWriter::addPng(const std::string& path, const Image& image) {
    const std::vector<unsigned char> png = encodePng(path, image);
    const StagedTemp t = stageFile<ImageError>(path, png.data(), png.size());
    keep(t.temp, path, t.slot);
}

void FileSetWriter::addFile(const std::string& path, const std::string& bytes) {
    const StagedTemp t = stageFile<std::runtime_error>(path, bytes.data(), bytes.size());
    keep(t.temp, path, t.slot);
}

void FileSetWriter::commit() {
    std::vector<Staged> files = std::move(staged_);
    staged_.clear();
    for (std::size_t i = 0; i < files.size(); ++i) {
        try {
            commitFile<std::runtime_error>({files[i].temp, files[i].slot}, files[i].target);
        } catch (...) {
            for (std::size_t j = i + 1; j < files.size(); ++j) {
                ::unlink(files[j].temp.c_str());
                untrackTemp(files[j].slot);
            }
            throw;
        }
    }
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
            for (int c = 0; c < 4; ++c)
                q[c] = std::uint8_t((sum[c] + unsigned(n) / 2) / unsigned(n));  // round to nearest
        }
    out.layout = image.layout.scaled(1.0 / factor);
    out.scale = image.scale;
    return out;
}

void blit(Image& dst, const Image& src, int x, int y) {
    x *= dst.scale;
    y *= dst.scale;
    const int x0 = std::max(0, x), y0 = std::max(0, y);
    const int x1 = std::min(dst.width, x + src.width), y1 = std::min(dst.height, y + src.height);
    dst.layout.append(src.layout, x, y);
    if (x0 >= x1) return;
    for (int row = y0; row < y1; ++row)
        std::memcpy(dst.pixel(x0, row), src.pixel(x0 - x, row - y), std::size_t(x1 - x0) * 4);
}

Image stackVertically(const Image& top, const Image& bottom) {
    Image out(std::max(top.width, bottom.width), top.height + bottom.height);
    blit(out, top, 0, 0);
    blit(out, bottom, 0, top.height);  // out.scale is 1 here: pixels
    out.scale = top.scale;
    return out;
}

void paintRect(Image& image, int x, int y, int w, int h, const Color& color) {
    auto byte = [](float channel) { return std::uint8_t(std::lround(std::clamp(channel, 0.0f, 1.0f) * 255)); };
    const std::uint8_t rgba[4] = {byte(color.r), byte(color.g), byte(color.b), 255};
    x *= image.scale, y *= image.scale, w *= image.scale, h *= image.scale;
    const int x0 = std::max(0, x), y0 = std::max(0, y);
    const int x1 = std::min(image.width, x + w), y1 = std::min(image.height, y + h);
    for (int row = y0; row < y1; ++row)
        for (int col = x0; col < x1; ++col) std::memcpy(image.pixel(col, row), rgba, 4);
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
