// Sweep and prune (core/broadphase/sweep_and_prune.h) against the O(n^2) testAabbAabb loop after every frame,
// and its swap count against the number of inversions of the old endpoint order under the new
// coordinates (verification/broad_phase_oracle.h).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <set>

#include "core/broadphase/sweep_and_prune.h"
#include "verification/broad_phase_oracle.h"

using namespace cdlab;
using broad_oracle::bruteForcePairs;
using broad_oracle::IdPair;
using broad_oracle::sortedPairs;

namespace {

std::vector<broad_oracle::End> orderOf(const SweepAndPrune& sap, int axis) {
    std::vector<broad_oracle::End> out;
    for (const SapEndpoint& e : sap.endpoints(axis)) out.push_back({e.object(), e.isMax()});
    return out;
}

/// The untraced update (its own insertion loop, sweep_and_prune.cpp) left `untraced` as the traced
/// one left `traced`: the same lists, ranks and pairs, and the same counts in the results.
void checkSameState(const SweepAndPrune& untraced, const SapResult& u, const SweepAndPrune& traced, const SapResult& t) {
    CHECK(u.status == t.status);
    CHECK(u.swaps == t.swaps);
    CHECK(u.pairsAdded == t.pairsAdded);
    CHECK(u.pairsRemoved == t.pairsRemoved);
    CHECK(untraced.counters().updates == traced.counters().updates);
    CHECK(untraced.counters().swaps == traced.counters().swaps);
    CHECK(untraced.counters().pairsAdded == traced.counters().pairsAdded);
    CHECK(untraced.counters().pairsRemoved == traced.counters().pairsRemoved);
    CHECK(sortedPairs(untraced.pairs()) == sortedPairs(traced.pairs()));
    for (int k = 0; k < 3; ++k) {
        CHECK(u.swapsPerAxis[k] == t.swapsPerAxis[k]);
        const auto& eu = untraced.endpoints(k);
        const auto& et = traced.endpoints(k);
        REQUIRE(eu.size() == et.size());
        for (std::size_t i = 0; i < eu.size(); ++i) {
            CHECK(eu[i].tag == et[i].tag);
            CHECK(untraced.rank(k, eu[i].object(), eu[i].isMax()) == static_cast<int>(i));
        }
    }
}

/// Update with `boxes`, then check pairs against brute force, the sortedness and ranks of the
/// lists, the trace's pair events against the set difference, and (if asked) swaps = inversions.
/// A copy updated without a trace must end in the same state.
void updateAndCheck(SweepAndPrune& sap, const std::vector<Aabb>& boxes, bool checkInversions,
                    const std::vector<char>* alive = nullptr) {
    std::int64_t expectedSwaps[3] = {0, 0, 0};
    if (checkInversions)
        for (int k = 0; k < 3; ++k) expectedSwaps[k] = broad_oracle::inversions(orderOf(sap, k), boxes, k);
    const std::vector<IdPair> before = sortedPairs(sap.pairs());
    SweepAndPrune untraced = sap;
    const SapResult u = untraced.update(boxes);
    SapTrace trace;
    const SapResult r = sap.update(boxes, &trace);
    REQUIRE(r.status == SapStatus::Ok);
    const std::vector<IdPair> after = sortedPairs(sap.pairs());
    REQUIRE(after == bruteForcePairs(boxes, alive));
    checkSameState(untraced, u, sap, r);
    for (int k = 0; k < 3; ++k) {
        const auto& e = sap.endpoints(k);
        for (std::size_t i = 0; i < e.size(); ++i) {
            CHECK(sap.rank(k, e[i].object(), e[i].isMax()) == static_cast<int>(i));
            if (i > 0)
                CHECK((e[i - 1].value < e[i].value ||
                       (e[i - 1].value == e[i].value && !(e[i - 1].isMax() && !e[i].isMax()))));
        }
        CHECK(trace.swapsPerAxis[k] == r.swapsPerAxis[k]);
        if (checkInversions) CHECK(r.swapsPerAxis[k] == expectedSwaps[k]);
    }
    CHECK(static_cast<std::int64_t>(trace.swaps.size()) == r.swaps);
    // Replaying the events on the old set gives the new set.
    std::set<IdPair> replay(before.begin(), before.end());
    std::size_t ia = 0, ir = 0;
    for (const SapSwap& s : trace.swaps) {
        const IdPair p{std::min(s.movingObject, s.passedObject), std::max(s.movingObject, s.passedObject)};
        if (s.event == SapPairEvent::Added) {
            REQUIRE(ia < trace.added.size());
            CHECK((IdPair{trace.added[ia].a, trace.added[ia].b} == p));
            ++ia;
            CHECK(replay.insert(p).second);
            CHECK(s.axesOverlapping == 3);
        } else if (s.event == SapPairEvent::Removed) {
            REQUIRE(ir < trace.removed.size());
            CHECK((IdPair{trace.removed[ir].a, trace.removed[ir].b} == p));
            ++ir;
            CHECK(replay.erase(p) == 1);
            CHECK(s.axesOverlapping == 2);
        }
    }
    CHECK(ia == trace.added.size());
    CHECK(ir == trace.removed.size());
    CHECK(std::vector<IdPair>(replay.begin(), replay.end()) == after);
}

/// Adds `box` without a trace, and to a copy with one: both must end in the same state.
SapResult addAndCheck(SweepAndPrune& sap, const Aabb& box) {
    SweepAndPrune traced = sap;
    SapTrace trace;
    const SapResult t = traced.add(box, &trace);
    const SapResult r = sap.add(box);
    REQUIRE(r.status == SapStatus::Ok);
    checkSameState(sap, r, traced, t);
    return r;
}

/// The boxes the structure holds now (last update / add), by id.
std::vector<Aabb> stored(const SweepAndPrune& sap) {
    std::vector<Aabb> out;
    for (int i = 0; i < sap.idCapacity(); ++i) out.push_back(sap.box(i));
    return out;
}

void buildAndCheck(SweepAndPrune& sap, const std::vector<Aabb>& boxes) {
    SapTrace trace;
    REQUIRE(sap.build(boxes, &trace).status == SapStatus::Ok);
    REQUIRE(sortedPairs(sap.pairs()) == bruteForcePairs(boxes));
    CHECK(sortedPairs(trace.added) == sortedPairs(sap.pairs()));
}

}  // namespace

TEST_SUITE("sweep_and_prune") {
    TEST_CASE("coherent random motion: pairs equal brute force after every frame, swaps = inversions") {
        for (std::uint64_t seed = 1; seed <= 30; ++seed) {
            std::mt19937_64 rng(seed);
            const int n = 20 + static_cast<int>(rng() % 60);
            auto m = broad_oracle::Motion::random(rng, n, 10.0, 0.2, 1.5, 0.15);
            SweepAndPrune sap;
            buildAndCheck(sap, m.boxes());
            for (int f = 0; f < 40; ++f) {
                m.step();
                updateAndCheck(sap, m.boxes(), seed <= 8);
            }
        }
    }

    TEST_CASE("integer coordinates: exact ties, touching faces, zero-size and identical boxes") {
        for (std::uint64_t seed = 1; seed <= 40; ++seed) {
            std::mt19937_64 rng(seed + 100);
            const int n = 10 + static_cast<int>(rng() % 30);
            std::vector<Aabb> boxes;
            for (int i = 0; i < n; ++i) boxes.push_back(broad_oracle::integerBox(rng, 6, seed % 3 == 0 ? 0 : 2));
            for (int i = 0; i < n / 4; ++i) boxes.push_back(boxes[rng() % boxes.size()]);  // identical copies
            SweepAndPrune sap;
            buildAndCheck(sap, boxes);
            for (int f = 0; f < 30; ++f) {
                // Integer steps of -1, 0, +1 per axis: every frame is full of exact ties.
                for (Aabb& b : boxes) {
                    const Vec3 d(static_cast<double>(rng() % 3) - 1.0, static_cast<double>(rng() % 3) - 1.0,
                                 static_cast<double>(rng() % 3) - 1.0);
                    b.min += d;
                    b.max += d;
                }
                updateAndCheck(sap, boxes, true);
            }
            // Additions full of ties (integer boxes, some of zero size), untraced beside a traced copy.
            for (int k = 0; k < 5; ++k) {
                const Aabb box = broad_oracle::integerBox(rng, 6, k % 2 ? 0 : 2);
                addAndCheck(sap, box);
                boxes.push_back(box);
                CHECK(sortedPairs(sap.pairs()) == bruteForcePairs(boxes));
            }
        }
    }

    TEST_CASE("touching boxes overlap (closed), a gap of one ulp separates") {
        std::vector<Aabb> boxes = {{Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(1, 0, 0), Vec3(2, 1, 1)}};
        SweepAndPrune sap;
        buildAndCheck(sap, boxes);
        CHECK(sap.pairs().size() == 1);
        const double gap = std::nextafter(1.0, 2.0);
        boxes[1] = {Vec3(gap, 0, 0), Vec3(2, 1, 1)};
        updateAndCheck(sap, boxes, true);
        CHECK(sap.pairs().empty());
        boxes[1] = {Vec3(1, 0, 0), Vec3(2, 1, 1)};
        updateAndCheck(sap, boxes, true);
        CHECK(sap.reported(0, 1));
        // Touching on y and z edges too (corner contact), and a point box on a face.
        boxes = {{Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(1, 1, 1), Vec3(2, 2, 2)}};
        updateAndCheck(sap, boxes, true);
        CHECK(sap.reported(0, 1));
        boxes[1] = {Vec3(1, 0.5, 0.5), Vec3(1, 0.5, 0.5)};
        updateAndCheck(sap, boxes, true);
        CHECK(sap.reported(0, 1));
    }

    TEST_CASE("huge offsets (1e6) and tiny sizes (1e-6 .. 1e-3)") {
        for (std::uint64_t seed = 1; seed <= 10; ++seed) {
            std::mt19937_64 rng(seed + 300);
            const double scale = seed % 2 ? 1e-3 : 1e-6;
            auto m = broad_oracle::Motion::random(rng, 50, 10 * scale, 0.2 * scale, 1.5 * scale, 0.2 * scale);
            const Vec3 offset(1e6, -1e6, 3e6);
            SweepAndPrune sap;
            buildAndCheck(sap, m.boxes(offset));
            for (int f = 0; f < 30; ++f) {
                m.step();
                updateAndCheck(sap, m.boxes(offset), seed <= 4);
            }
        }
    }

    TEST_CASE("teleports: incoherent jumps still give exact pairs and swaps = inversions") {
        for (std::uint64_t seed = 1; seed <= 10; ++seed) {
            std::mt19937_64 rng(seed + 400);
            auto m = broad_oracle::Motion::random(rng, 60, 8.0, 0.3, 1.2, 0.1);
            SweepAndPrune sap;
            buildAndCheck(sap, m.boxes());
            for (int f = 0; f < 20; ++f) {
                m.step();
                if (f % 3 == 0)  // teleport a third of the boxes anywhere
                    for (std::size_t i = 0; i < m.center.size(); i += 3)
                        m.center[i] = Vec3(broad_oracle::uniform(rng, 0, 8), broad_oracle::uniform(rng, 0, 8),
                                           broad_oracle::uniform(rng, 0, 8));
                if (f == 10)  // everything reversed: the most swaps
                    for (Vec3& c : m.center) c = Vec3(8, 8, 8) - c;
                updateAndCheck(sap, m.boxes(), true);
            }
        }
    }

    TEST_CASE("add and remove mid-sequence, ids are stable") {
        for (std::uint64_t seed = 1; seed <= 15; ++seed) {
            std::mt19937_64 rng(seed + 500);
            auto m = broad_oracle::Motion::random(rng, 30, 8.0, 0.3, 1.2, 0.1);
            SweepAndPrune sap;
            buildAndCheck(sap, m.boxes());
            std::vector<char> alive(30, 1);
            for (int f = 0; f < 40; ++f) {
                m.step();
                // A random removal or addition, checked on its own before the update.
                if (rng() % 2 && sap.objectCount() > 2) {
                    int id;
                    do id = static_cast<int>(rng() % sap.idCapacity());
                    while (!alive[id]);
                    SapTrace t;
                    const std::vector<IdPair> beforePairs = sortedPairs(sap.pairs());
                    REQUIRE(sap.remove(id, &t).status == SapStatus::Ok);
                    alive[id] = 0;
                    for (const BoxPair& p : t.removed) CHECK((p.a == id || p.b == id));
                    int had = 0;
                    for (const IdPair& p : beforePairs) had += (p.a == id || p.b == id);
                    CHECK(static_cast<int>(t.removed.size()) == had);
                    CHECK(sortedPairs(sap.pairs()) == bruteForcePairs(stored(sap), &alive));
                } else {
                    const Aabb nb{Vec3(broad_oracle::uniform(rng, 0, 8), broad_oracle::uniform(rng, 0, 8),
                                       broad_oracle::uniform(rng, 0, 8)),
                                  Vec3::Zero()};
                    Aabb box = nb;
                    box.max = box.min + Vec3(1, 1, 1);
                    const int id = addAndCheck(sap, box).object;
                    if (id >= static_cast<int>(m.center.size())) {
                        m.center.push_back(Vec3::Zero());
                        m.half.push_back(Vec3::Zero());
                        m.velocity.push_back(Vec3::Zero());
                        alive.push_back(0);
                    }
                    CHECK(!alive[id]);  // a fresh or a freed id
                    alive[id] = 1;
                    m.center[id] = box.min + Vec3(0.5, 0.5, 0.5);
                    m.half[id] = Vec3(0.5, 0.5, 0.5);
                    m.velocity[id] = Vec3(0.05, -0.03, 0.02);
                    CHECK(sortedPairs(sap.pairs()) == bruteForcePairs(stored(sap), &alive));
                }
                updateAndCheck(sap, m.boxes(), false, &alive);
                CHECK(sap.objectCount() == static_cast<int>(std::count(alive.begin(), alive.end(), 1)));
            }
        }
    }

    TEST_CASE("NaN, inf, empty boxes and a wrong count are rejected and change nothing") {
        std::vector<Aabb> boxes = {
            {Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(0.5, 0.5, 0.5), Vec3(2, 2, 2)}, {Vec3(5, 5, 5), Vec3(6, 6, 6)}};
        SweepAndPrune sap;
        buildAndCheck(sap, boxes);
        const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
        std::vector<Aabb> bad = boxes;
        bad[2].min.y() = nan;
        SapResult r = sap.update(bad);
        CHECK(r.status == SapStatus::NonFiniteBox);
        CHECK(r.object == 2);
        bad = boxes;
        bad[1].max.z() = inf;
        CHECK(sap.update(bad).status == SapStatus::NonFiniteBox);
        bad = boxes;
        bad[0].min.x() = 2;  // min > max
        r = sap.update(bad);
        CHECK(r.status == SapStatus::EmptyBox);
        CHECK(r.object == 0);
        CHECK(sap.update(std::vector<Aabb>(2)).status == SapStatus::WrongBoxCount);
        CHECK(sap.add(Aabb{Vec3(0, 0, 0), Vec3(nan, 1, 1)}).status == SapStatus::NonFiniteBox);
        CHECK(sap.add(Aabb{Vec3(0, 0, 0), Vec3(-1, 1, 1)}).status == SapStatus::EmptyBox);
        CHECK(sap.remove(7).status == SapStatus::UnknownId);
        CHECK(sap.build({boxes[0], Aabb{Vec3(0, 0, 0), Vec3(-inf, 0, 0)}}).status == SapStatus::NonFiniteBox);
        // State untouched: the next valid update still matches brute force.
        CHECK(sap.objectCount() == 3);
        updateAndCheck(sap, boxes, true);
        CHECK(sap.pairs().size() == 1);
    }

    TEST_CASE("additions to an empty structure, untraced and traced alike") {
        std::mt19937_64 rng(11);
        SweepAndPrune sap;
        std::vector<Aabb> boxes;
        for (int k = 0; k < 12; ++k) {
            const Aabb box = broad_oracle::integerBox(rng, 3, k % 3 == 0 ? 0 : 1);
            CHECK(addAndCheck(sap, box).object == k);
            boxes.push_back(box);
            CHECK(sortedPairs(sap.pairs()) == bruteForcePairs(boxes));
        }
    }

    TEST_CASE("counters accumulate, a still frame swaps nothing") {
        std::mt19937_64 rng(7);
        auto m = broad_oracle::Motion::random(rng, 40, 6.0, 0.3, 1.0, 0.1);
        SweepAndPrune sap;
        sap.reserve(40, 200);
        buildAndCheck(sap, m.boxes());
        std::int64_t swaps = 0, added = 0, removed = 0;
        for (int f = 0; f < 10; ++f) {
            m.step();
            const SapResult r = sap.update(m.boxes());
            swaps += r.swaps;
            added += r.pairsAdded;
            removed += r.pairsRemoved;
        }
        CHECK(sap.counters().updates == 10);
        CHECK(sap.counters().swaps == swaps);
        // build() reset the counters and reported the initial pairs as added.
        CHECK(sap.counters().pairsAdded - sap.counters().pairsRemoved == static_cast<std::int64_t>(sap.pairs().size()));
        CHECK(sap.counters().pairsRemoved == removed);
        const SapResult still = sap.update(m.boxes());
        CHECK(still.swaps == 0);
        CHECK(still.pairsAdded + still.pairsRemoved == 0);
    }

}  // TEST_SUITE
