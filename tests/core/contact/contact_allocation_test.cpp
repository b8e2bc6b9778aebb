// The contact generators make no heap allocation per call (issue: "zero heap allocations per call,
// prove it with a counting allocator"): box–box, box–plane and the general SAT on hulls of 16 and
// 64 vertices, untraced. The global operator new of this test executable counts calls on the
// current thread.
#include <doctest/doctest.h>

#include <cstdlib>
#include <new>
#include <random>

#include "core/contact/contact_box.h"
#include "core/geometry/convex_hull.h"
#include "core/geometry/polyhedron_presets.h"
#include "verification/minkowski_facet_oracle.h"
#include "tests/core/contact/random_pose.h"

namespace {
thread_local long long g_allocations = 0;
int* volatile g_sink = nullptr;  // keeps the compiler from eliding the probe allocation
}

// Every unaligned form is replaced, so that whatever allocates (std::stable_sort's nothrow
// temporary buffer included) frees through the same malloc / free pair: under AddressSanitizer,
// which intercepts the forms left alone, a mixed pair is an alloc-dealloc mismatch.
namespace {
void* counted(std::size_t n) noexcept {
    ++g_allocations;
    return std::malloc(n ? n : 1);
}
}  // namespace

void* operator new(std::size_t n) {
    if (void* p = counted(n)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
    if (void* p = counted(n)) return p;
    throw std::bad_alloc();
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return counted(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return counted(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

using namespace cdlab;

namespace {

template <class F>
long long allocationsOf(F&& f) {
    const long long before = g_allocations;
    f();
    return g_allocations - before;
}

}  // namespace

TEST_SUITE("contact_allocation") {
    TEST_CASE("the counter counts") {
        CHECK(allocationsOf([] { g_sink = new int(1); }) == 1);
        delete g_sink;
    }

    TEST_CASE("box-box, box-plane and hull-hull contacts allocate nothing per call") {
        std::mt19937_64 rng(3);
        ConvexPolyhedron hulls[2];
        for (int i = 0; i < 2; ++i) {
            const int n = i == 0 ? 16 : 64;
            const std::vector<Vec3> pts = test::randomPolytope(rng, n, 1.0, Vec3::Zero());
            hulls[i] = convexHull(pts).polyhedron;
            REQUIRE(hulls[i].vertexCount() >= n / 2);
        }
        int collidingBoxes = 0, collidingPlane = 0, collidingHulls = 0;
        for (int k = 0; k < 200; ++k) {
            const Transform ta = test::randomPose(rng, Vec3::Zero(), 0.0), tb = test::randomPose(rng, Vec3::Zero(), 0.8);
            const Plane plane{test::randomUnit(rng), 0.1};
            CHECK(allocationsOf([&] {
                      collidingBoxes += contactBoxBox(Vec3(0.5, 0.4, 0.3), ta, Vec3(0.6, 0.2, 0.4), tb).colliding();
                  }) == 0);
            CHECK(allocationsOf([&] {
                      collidingPlane += contactBoxPlane(Vec3(0.5, 0.4, 0.3), tb, plane).colliding();
                  }) == 0);
            const ConvexPolyhedron& h = hulls[k % 2];
            CHECK(allocationsOf([&] { collidingHulls += contactPolyhedra(h, ta, h, tb).colliding(); }) == 0);
        }
        CHECK(collidingBoxes > 40);  // the manifold branches ran, not only the early outs
        CHECK(collidingPlane > 40);
        CHECK(collidingHulls > 40);
    }
}
