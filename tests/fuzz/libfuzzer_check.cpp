// libFuzzer entry point for `cdlab check` (built with -DCDLAB_FUZZ=ON by clang: ./cdlab fuzz check).
#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    cdlab::fuzz::fuzzCheck(data, size);
    return 0;
}
