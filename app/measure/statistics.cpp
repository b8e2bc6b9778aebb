#include "app/measure/statistics.h"

#include <time.h>

#include <algorithm>
#include <cmath>

namespace cdlab::demos {

double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const std::size_t h = v.size() / 2;
    return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

double threadSeconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double centroidRadius(const std::vector<Vec3>& points) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& x : points) c += x;
    c /= static_cast<double>(points.size());
    double r = 0;
    for (const Vec3& x : points) r = std::max(r, (x - c).norm());
    return r;
}

}  // namespace cdlab::demos
