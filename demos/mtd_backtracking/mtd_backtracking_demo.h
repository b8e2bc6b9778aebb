// demo_mtd_backtracking: three ways out of a penetration found at the end of a time step, side by
// side — the minimum translational distance (EPA's depth · n), backtracking along the motion to the
// time of impact (the linear cast), and conservative advancement along the true, turning motion.
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& mtdBacktrackingDemo();

}  // namespace cdlab::demos
