// libFuzzer entry point for drawing scenes, bounded to small images (built with -DCDLAB_FUZZ=ON by
// clang: ./cdlab fuzz render).
#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    cdlab::fuzz::fuzzRender(data, size);
    return 0;
}
