// libFuzzer entry point for scene loading (built with -DCDLAB_FUZZ=ON by clang: ./cdlab fuzz).
#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    cdlab::fuzz::fuzzScene(data, size);
    return 0;
}
