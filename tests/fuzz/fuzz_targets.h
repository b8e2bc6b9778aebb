// Fuzz targets for cdlab's two text entry points, shared by the libFuzzer executables
// (tests/fuzz/libfuzzer_*.cpp, built by `./cdlab fuzz` with clang) and the bounded mutation run
// that ctest does (tests/fuzz/fuzz_smoke_test.cpp). A target returns normally when the input was
// handled as the contract says (an answer, or one clear input error) and calls std::abort() with
// a message on stderr when it was not, which both drivers report as a crash.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace cdlab::fuzz {

/// `cdlab query`: the bytes are JSON Lines. Every non-blank line gets exactly one answer line that
/// is valid JSON starting with "id"; an error answer is an input error (never "internal error");
/// a success answer holds no NaN/Inf (null) values, distances and depths are >= 0, normals unit.
void fuzzQuery(const std::uint8_t* data, std::size_t size);

/// Scene loading: the bytes are a scene file. It loads, or fails with an InputError naming
/// the source; a loaded scene then runs numerically (no GL) without any other exception.
void fuzzScene(const std::uint8_t* data, std::size_t size);

/// Scene drawing, bounded: the bytes are a scene file. It loads (or fails as fuzzScene requires),
/// and a scene that loads is drawn with one GL context for the whole run at a small image size
/// (kFuzzImageSide² pixels, or the smallest layout the demo accepts up to 1024 x 768; scale 1), so
/// that every input's cost stays bounded. Every frame must then be a whole image, and any error an input error naming
/// the source: a GL error, a crash or another exception is a contract violation.
void fuzzRender(const std::uint8_t* data, std::size_t size);
constexpr int kFuzzImageSide = 96;

/// `cdlab check`: the bytes are JSON Lines a student handed in. The run never throws; it prints
/// exactly one verdict line per non-blank input line ("line <k>" in order, then ": pass" or
/// ": FAIL"), then "<passed> passed, <failed> failed" with the right counts, and no byte below
/// 0x20 but the line ends (nothing a line holds can forge a verdict or hide one). And cdlab's own
/// answer to every line that is a valid query, handed back as the answer, passes.
void fuzzCheck(const std::uint8_t* data, std::size_t size);

/// What is wrong with one answer line of `cdlab query` ("" when it keeps the contract above).
std::string queryAnswerViolation(const std::string& line);

/// Reports a broken contract and aborts.
[[noreturn]] void contractViolation(const std::string& what, const std::string& input);

}  // namespace cdlab::fuzz
