// Floating-point expansion arithmetic (Shewchuk 1997) and the exact predicates built on it.
#include "core/base/exact_predicates.h"

#include <algorithm>
#include <cstddef>

namespace cdlab::exact {

using dd::fastTwoSum;

int Expansion::sign() const {
    if (components_.empty()) return 0;
    // Nonoverlapping components: the largest one alone decides the sign of the sum.
    const double top = components_.back();
    return (top > 0.0) - (top < 0.0);
}

double Expansion::estimate() const {
    double sum = 0.0;
    for (double c : components_) sum += c;
    return sum;
}

// Fast expansion sum with zero elimination (Shewchuk Thm. 13, fast_expansion_sum_zeroelim):
// merge both component lists by increasing magnitude, then run one two-sum chain through them,
// emitting each roundoff. With round-to-even the result is strongly nonoverlapping when the
// inputs are. (Shewchuk's first step uses Fast-Two-Sum; Two-Sum gives identical results.)
Expansion operator+(const Expansion& e, const Expansion& f) {
    if (e.components_.empty()) return f;
    if (f.components_.empty()) return e;
    std::vector<double> merged(e.components_.size() + f.components_.size());
    std::merge(e.components_.begin(), e.components_.end(), f.components_.begin(), f.components_.end(), merged.begin(),
               [](double x, double y) { return std::abs(x) < std::abs(y); });
    Expansion h;
    h.components_.reserve(merged.size());
    double q = merged[0];
    for (std::size_t i = 1; i < merged.size(); ++i) {
        double sum, roundoff;
        twoSum(q, merged[i], sum, roundoff);
        if (roundoff != 0.0) h.components_.push_back(roundoff);
        q = sum;
    }
    if (q != 0.0) h.components_.push_back(q);
    h.compress();
    return h;
}

Expansion Expansion::operator-() const {
    Expansion negated = *this;
    for (double& c : negated.components_) c = -c;
    return negated;
}

Expansion operator-(const Expansion& e, const Expansion& f) { return e + (-f); }

// Shewchuk's scale_expansion_zeroelim (Thm. 19): maintains nonoverlapping, and with
// round-to-even the strongly nonoverlapping and nonadjacent properties.
Expansion Expansion::scale(const Expansion& e, double b) {
    Expansion h;
    if (e.components_.empty() || b == 0.0) return h;
    h.components_.reserve(2 * e.components_.size());
    double q, roundoff;
    twoProduct(e.components_[0], b, q, roundoff);
    if (roundoff != 0.0) h.components_.push_back(roundoff);
    for (std::size_t i = 1; i < e.components_.size(); ++i) {
        double productHi, productLo, sum;
        twoProduct(e.components_[i], b, productHi, productLo);
        twoSum(q, productLo, sum, roundoff);
        if (roundoff != 0.0) h.components_.push_back(roundoff);
        fastTwoSum(productHi, sum, q, roundoff);  // |productHi| >= |sum| (Shewchuk's proof)
        if (roundoff != 0.0) h.components_.push_back(roundoff);
    }
    if (q != 0.0) h.components_.push_back(q);
    return h;
}

// e * f = sum over the components f_j of e * f_j.
Expansion operator*(const Expansion& e, const Expansion& f) {
    const Expansion& longer = e.components_.size() >= f.components_.size() ? e : f;
    const Expansion& shorter = e.components_.size() >= f.components_.size() ? f : e;
    Expansion product;
    for (double b : shorter.components_) product = product + Expansion::scale(longer, b);
    return product;
}

// Shewchuk's compress (§2.8): two sweeps of Fast-Two-Sum, top-down then bottom-up. The result
// is nonadjacent (hence strongly nonoverlapping) and usually much shorter.
void Expansion::compress() {
    std::vector<double>& g = components_;
    const int n = static_cast<int>(g.size());
    if (n <= 1) return;
    int bottom = n - 1;
    double q = g[bottom];
    for (int i = n - 2; i >= 0; --i) {
        double sum, roundoff;
        fastTwoSum(q, g[i], sum, roundoff);
        if (roundoff != 0.0) {
            g[bottom--] = sum;
            q = roundoff;
        } else {
            q = sum;
        }
    }
    int top = 0;
    for (int i = bottom + 1; i < n; ++i) {
        double sum, roundoff;
        fastTwoSum(g[i], q, sum, roundoff);
        if (roundoff != 0.0) g[top++] = roundoff;
        q = sum;
    }
    g[top] = q;
    g.resize(static_cast<std::size_t>(top) + 1);
    std::erase(g, 0.0);  // a zero can only survive as the whole value
}

namespace {

// filteredSign for the predicates below, which read exactly the given points: one range check
// of their coordinates replaces the per-expression bookkeeping.
template <class Expression>
int predicateSign(const Expression& expression, std::initializer_list<const Vec3*> points, bool* usedExact = nullptr) {
    const int s = certainSign(expression(Bounded{}));
    if (usedExact) *usedExact = (s == 0);
    if (s != 0) return s;
    return exactSign(expression, inExpansionRange(points));
}

}  // namespace

int dotSign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, bool* usedExact) {
    return predicateSign([&](auto zero) { return dotOfDifferences<decltype(zero)>(a, b, c, d); }, {&a, &b, &c, &d},
                         usedExact);
}

int orient3dSign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, bool* usedExact) {
    return predicateSign([&](auto zero) { return orient3d<decltype(zero)>(a, b, c, d); }, {&a, &b, &c, &d}, usedExact);
}

int edgeSideSign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p, bool* usedExact) {
    return predicateSign([&](auto zero) { return edgeSide<decltype(zero)>(a, b, c, p); }, {&a, &b, &c, &p}, usedExact);
}

bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
    for (int i = 0; i < 3; ++i) {
        if (predicateSign([&](auto zero) { return crossComponent<decltype(zero)>(a, b, c, i); }, {&a, &b, &c}) != 0)
            return false;
    }
    return true;
}

}  // namespace cdlab::exact
