// libFuzzer entry point for `cdlab query` (built with -DCDLAB_FUZZ=ON by clang: ./cdlab fuzz).
#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    cdlab::fuzz::fuzzQuery(data, size);
    return 0;
}
