// PNG I/O, atomic writes and the small image helpers (no GL needed).
#include <doctest/doctest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "render/gif_writer.h"
#include "render/image.h"

using namespace cdlab::render;
namespace fs = std::filesystem;

namespace {

/// A per-process scratch folder, removed at exit.
struct TempDir {
    fs::path path = fs::temp_directory_path() / ("cdlab_image_test_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};
const fs::path& tempDir() {
    static TempDir dir;
    return dir.path;
}

/// Deterministic noise with every channel, alpha included (LCG: Numerical Recipes constants).
Image noise(int w, int h, std::uint32_t seed) {
    Image im(w, h);
    for (auto& b : im.rgba) {
        seed = seed * 1664525u + 1013904223u;
        b = std::uint8_t(seed >> 24);
    }
    return im;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string errorOf(auto&& f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_SUITE("render/image") {
    TEST_CASE("PNG round trip keeps every byte, alpha included, and encodes deterministically") {
        const Image im = noise(37, 23, 7);                                     // odd sizes: no row padding assumptions
        const std::string path = (tempDir() / "round" / "trip.png").string();  // parent created on demand
        writePngAtomic(path, im);
        const Image back = readPng(path);
        CHECK(back.width == 37);
        CHECK(back.height == 23);
        CHECK(back.rgba == im.rgba);
        CHECK(pixelHash(back) == pixelHash(im));
        const std::string first = slurp(path);
        writePngAtomic(path, im);  // overwrite: same pixels -> same bytes (no timestamps)
        CHECK(slurp(path) == first);
    }

    TEST_CASE("atomic writes leave no temp files behind") {
        const fs::path dir = tempDir() / "atomic";
        writePngAtomic((dir / "a.png").string(), noise(8, 8, 1));
        writeFileAtomic((dir / "b.json").string(), "{\"x\": 1}\n");
        writeFileAtomic((dir / "b.json").string(), "{\"x\": 2}\n");
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        CHECK(names == std::vector<std::string>{"a.png", "b.json"});
        CHECK(slurp(dir / "b.json") == "{\"x\": 2}\n");
    }

    TEST_CASE("an unwritable folder is reported in one line naming the file") {
        // A regular file where a folder should be: fails even for root (chmod would not).
        const fs::path blocker = tempDir() / "blocker";
        writeFileAtomic(blocker.string(), "x");
        const std::string target = (blocker / "sub" / "out.png").string();
        const std::string msg = errorOf([&] { writePngAtomic(target, noise(4, 4, 2)); });
        CHECK(msg.find(target) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
        CHECK_THROWS_AS(writePngAtomic(target, noise(4, 4, 2)), ImageError);
        CHECK_THROWS_AS(writeFileAtomic(target, "x"), std::runtime_error);
    }

    TEST_CASE("a write error mid-file (full disk) throws, names the file and removes the temp file") {
        // RLIMIT_FSIZE makes write() fail with EFBIG once the file reaches the limit: the same
        // code path as ENOSPC on a full disk.
        const fs::path dir = tempDir() / "full";
        fs::create_directories(dir);
        rlimit old{};
        REQUIRE(getrlimit(RLIMIT_FSIZE, &old) == 0);
        auto oldHandler = std::signal(SIGXFSZ, SIG_IGN);
        rlimit small = old;
        small.rlim_cur = 1000;
        REQUIRE(setrlimit(RLIMIT_FSIZE, &small) == 0);
        const std::string target = (dir / "big.png").string();
        const std::string msg = errorOf([&] { writePngAtomic(target, noise(64, 64, 3)); });  // ~16 KB of noise
        setrlimit(RLIMIT_FSIZE, &old);
        std::signal(SIGXFSZ, oldHandler);
        CHECK(msg.find(target) != std::string::npos);
        CHECK(fs::is_empty(dir));  // neither the target nor a temp file
    }

    TEST_CASE("readPng says which file and what is wrong") {
        const fs::path dir = tempDir() / "bad";
        const std::string missing = (dir / "missing.png").string();
        std::string msg = errorOf([&] { readPng(missing); });
        CHECK(msg.find(missing) != std::string::npos);
        CHECK_THROWS_AS(readPng(missing), ImageError);

        const std::string text = (dir / "text.png").string();
        writeFileAtomic(text, "this is not an image\n");
        msg = errorOf([&] { readPng(text); });
        CHECK(msg.find(text) != std::string::npos);
        CHECK(msg.find("not a PNG") != std::string::npos);

        const std::string empty = (dir / "empty.png").string();
        writeFileAtomic(empty, "");
        CHECK(errorOf([&] { readPng(empty); }).find("empty") != std::string::npos);

        const std::string good = (dir / "good.png").string();
        writePngAtomic(good, noise(40, 40, 4));
        const std::string bytes = slurp(good);
        const std::string cut = (dir / "cut.png").string();
        writeFileAtomic(cut, bytes.substr(0, bytes.size() / 2));
        msg = errorOf([&] { readPng(cut); });
        CHECK(msg.find(cut) != std::string::npos);
        CHECK(msg.find("truncated") != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }

    TEST_CASE("readPng: a directory, a huge header and an endless file are one line each") {
        // A golden PNG replaced by a folder (rm golden/.../step_01.png && mkdir golden/.../step_01.png)
        // once made cdlab golden print "basic_filebuf::underflow error reading the file: Is a directory".
        const fs::path dir = tempDir() / "hostile_png";
        fs::create_directories(dir / "dir.png");
        std::string msg = errorOf([&] { readPng((dir / "dir.png").string()); });
        CHECK(msg == "cannot read '" + (dir / "dir.png").string() + "': is a directory, not a file");
        CHECK_THROWS_AS(readPng((dir / "dir.png").string()), ImageError);

        // A valid PNG whose IHDR claims 10000 x 10000 pixels (400 MB decoded): refused from the
        // header, before stb_image allocates (stb does not check the CRC, so none is fixed up).
        writePngAtomic((dir / "small.png").string(), noise(4, 4, 6));
        std::string bytes = slurp(dir / "small.png");
        for (int offset : {16, 20}) {  // IHDR width, height: big-endian after "\x89PNG....IHDR"
            const std::uint32_t v = 10000;
            for (int i = 0; i < 4; ++i) bytes[offset + i] = char(v >> (24 - 8 * i));
        }
        writeFileAtomic((dir / "huge.png").string(), bytes);
        msg = errorOf([&] { readPng((dir / "huge.png").string()); });
        CHECK(msg.find("10000 x 10000 pixels, more than the limit") != std::string::npos);

        std::string content, problem;
        CHECK_FALSE(readFileBounded("/dev/zero", std::size_t(1) << 20, "a test file", content, problem));
        CHECK(problem == "larger than the 1 MiB limit for a test file");
        CHECK(content.empty());
        writeFileAtomic((dir / "three.txt").string(), "abc");
        CHECK(readFileBounded((dir / "three.txt").string(), 3, "x", content, problem));
        CHECK(content == "abc");
        CHECK_FALSE(readFileBounded((dir / "three.txt").string(), 2, "x", content, problem));
        CHECK(problem == "larger than the 2 bytes limit for x");
    }

    TEST_CASE("FileSetWriter replaces a set of files together, or none of them") {
        const fs::path dir = tempDir() / "set";
        writeFileAtomic((dir / "a.txt").string(), "old a");
        writeFileAtomic((dir / "b.txt").string(), "old b");
        const auto names = [&] {
            std::vector<std::string> n;
            for (const auto& e : fs::directory_iterator(dir)) n.push_back(e.path().filename().string());
            std::sort(n.begin(), n.end());
            return n;
        };
        {  // dropped without commit: nothing changes, no temp file stays
            FileSetWriter set;
            set.addFile((dir / "a.txt").string(), "new a");
            set.addPng((dir / "c.png").string(), noise(4, 4, 7));
        }
        CHECK(names() == std::vector<std::string>{"a.txt", "b.txt"});
        CHECK(slurp(dir / "a.txt") == "old a");

        fs::create_directories(dir / "d.txt");  // a target that cannot be written
        {  // a failure while staging: the caller never commits, the staged files go with the writer
            FileSetWriter bad;
            bad.addFile((dir / "a.txt").string(), "new a");
            CHECK_THROWS_WITH_AS(bad.addFile((dir / "d.txt").string(), "x"), doctest::Contains("is a directory"),
                                 std::runtime_error);
        }
        CHECK(slurp(dir / "a.txt") == "old a");
        CHECK(names() == std::vector<std::string>{"a.txt", "b.txt", "d.txt"});

        FileSetWriter good;
        good.addFile((dir / "a.txt").string(), "new a");
        good.addFile((dir / "b.txt").string(), "new b");
        good.commit();
        CHECK(slurp(dir / "a.txt") == "new a");
        CHECK(slurp(dir / "b.txt") == "new b");
        CHECK(names() == std::vector<std::string>{"a.txt", "b.txt", "d.txt"});
    }

    TEST_CASE("writePngAtomic rejects an inconsistent image") {
        Image im(4, 4);
        im.rgba.resize(10);
        CHECK_THROWS_AS(writePngAtomic((tempDir() / "x.png").string(), im), ImageError);
        CHECK_THROWS_AS(writePngAtomic((tempDir() / "y.png").string(), Image()), ImageError);
    }

    TEST_CASE("GIF encoding gives the same bytes on several threads at once as alone") {
        // giflib's colour quantisation keeps the axis it sorts on in a file-static variable: two
        // threads quantising at once changed each other's palettes (`cdlab figures` on workers wrote
        // a different animation.gif from run to run) until encodeGif took one at a time.
        std::mt19937 rng(7);
        std::uniform_int_distribution<int> byte(0, 255);
        std::vector<std::vector<Image>> animations(4);
        for (auto& frames : animations)
            for (int f = 0; f < 2; ++f) {
                Image im(96, 96);
                for (auto& c : im.rgba) c = static_cast<std::uint8_t>(byte(rng));
                frames.push_back(im);
            }
        std::vector<std::string> alone;
        for (const auto& frames : animations) alone.push_back(encodeGif(frames));
        for (int round = 0; round < 5; ++round) {
            std::vector<std::string> together(animations.size());
            std::vector<std::thread> threads;
            for (std::size_t k = 0; k < animations.size(); ++k)
                threads.emplace_back([&, k] { together[k] = encodeGif(animations[k]); });
            for (std::thread& t : threads) t.join();
            CHECK(together == alone);
        }
    }

    TEST_CASE("downsample averages each block with rounding") {
        Image im(4, 2);
        // Block (0,0): red values 0, 1, 2, 2 -> 5/4 = 1.25 -> 1; block (1,0): 255 x 3 + 0 -> 191.25 -> 191.
        const std::uint8_t reds[2][4] = {{0, 1, 255, 255}, {2, 2, 255, 0}};
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 4; ++x) {
                im.pixel(x, y)[0] = reds[y][x];
                im.pixel(x, y)[3] = 255;
            }
        const Image d = downsample(im, 2);
        REQUIRE(d.width == 2);
        REQUIRE(d.height == 1);
        CHECK(int(d.pixel(0, 0)[0]) == 1);
        CHECK(int(d.pixel(1, 0)[0]) == 191);
        CHECK(int(d.pixel(1, 0)[3]) == 255);
        CHECK(downsample(im, 1).rgba == im.rgba);
    }

    TEST_CASE("blit clips at every edge") {
        Image dst(4, 4), src(3, 3);
        for (auto& b : src.rgba) b = 9;
        blit(dst, src, -1, 2);  // covers x 0..1, y 2..3
        int painted = 0;
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x)
                if (dst.pixel(x, y)[0] == 9) {
                    ++painted;
                    CHECK(x <= 1);
                    CHECK(y >= 2);
                }
        CHECK(painted == 4);
        blit(dst, src, 10, 10);  // fully outside: no-op, no crash
        blit(dst, src, -10, -10);
    }

    TEST_CASE("pixelHash sees one changed bit and the shape") {
        Image a = noise(8, 8, 5), b = a;
        CHECK(pixelHash(a) == pixelHash(b));
        b.rgba[100] ^= 1;
        CHECK(pixelHash(a) != pixelHash(b));
        Image wide = noise(16, 4, 5), tall = wide;
        tall.width = 4, tall.height = 16;  // same bytes, other shape
        CHECK(pixelHash(wide) != pixelHash(tall));
    }
}
