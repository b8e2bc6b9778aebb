// Scaling by a power of two with multiplications instead of std::ldexp calls (a library call, ~50
// instructions each, where a multiplication is one): for scalings computed once and applied to
// many coordinates.
#pragma once

#include <cmath>

namespace cdlab {

/// x · 2^k rounded as std::ldexp(x, k) rounds it, for k in [-1074, 2046]. For k <= 1023, 2^k is a
/// double (normal, or subnormal below -1022) and one correctly rounded product is ldexp's value,
/// subnormal results included. Above, x · 2^1023 · 2^(k - 1023) scales up: both products are exact
/// until the result overflows, to inf as in ldexp. Made once per k, applied to many x.
class PowerOfTwo {
public:
    explicit PowerOfTwo(int k)
        : first_(std::ldexp(1.0, k <= 1023 ? k : 1023)), second_(k <= 1023 ? 1.0 : std::ldexp(1.0, k - 1023)) {}
    double operator()(double x) const { return x * first_ * second_; }

private:
    double first_, second_;
};

}  // namespace cdlab
