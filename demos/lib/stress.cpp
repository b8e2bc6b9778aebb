#include "demos/lib/stress.h"

#include <iostream>

namespace cdlab::demos {

int runStress(int, char**) {
    std::cerr << "cdlab stress: not available in this build\n";
    return 2;
}

}  // namespace cdlab::demos
