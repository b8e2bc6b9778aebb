#include "demos/lib/bench.h"

#include <iostream>

namespace cdlab::demos {

int runBench(int, char**) {
    std::cerr << "cdlab bench: not built yet\n";
    return 2;
}

}  // namespace cdlab::demos
