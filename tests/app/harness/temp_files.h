// The atomic writes' temp files (render/image.cpp: "<path>.tmp.<pid>.<n>, then rename"), which a
// finished or killed run must not leave behind.
#pragma once

#include <filesystem>
#include <string>

namespace cdlab::test {

inline bool isTempFile(const std::filesystem::path& p) { return p.filename().string().find(".tmp.") != std::string::npos; }

}  // namespace cdlab::test
