// Peers for `cdlab bench` (see app/bench/peers/bench_peers.h). Built only when libccd and / or Bullet
// (double precision) are installed: CDLAB_HAVE_CCD, CDLAB_HAVE_BULLET.
#include "app/bench/peers/bench_peers.h"

#include <algorithm>
#include <cmath>
#include <memory>

#if CDLAB_HAVE_CCD
#include <ccd/ccd.h>
#include <ccd/vec3.h>
#endif
#if CDLAB_HAVE_BULLET
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btConvexPolyhedron.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPolyhedralContactClipping.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <time.h>
#endif

namespace cdlab::demos {

namespace {

#if CDLAB_HAVE_CCD
// libccd object: cdlab's support mapping plus the centroid MPR starts from.
struct CcdObject {
    const PolytopeShape* shape = nullptr;
    Vec3 center = Vec3::Zero();
};

void ccdSupport(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
    const auto* o = static_cast<const CcdObject*>(obj);
    const Vec3 p = o->shape->support(Vec3(ccdVec3X(dir), ccdVec3Y(dir), ccdVec3Z(dir)));
    ccdVec3Set(out, p.x(), p.y(), p.z());
}

void ccdCenter(const void* obj, ccd_vec3_t* center) {
    const auto* o = static_cast<const CcdObject*>(obj);
    ccdVec3Set(center, o->center.x(), o->center.y(), o->center.z());
}

struct CcdSet {
    std::vector<CcdObject> a, b;
    ccd_t ccd;
};

std::shared_ptr<CcdSet> makeCcdSet(const std::vector<PeerPair>& pairs) {
    auto set = std::make_shared<CcdSet>();
    for (const PeerPair& p : pairs) {
        set->a.push_back({p.a, vertexCentroid(*p.va)});
        set->b.push_back({p.b, vertexCentroid(*p.vb)});
    }
    CCD_INIT(&set->ccd);  // libccd's defaults: epa / mpr tolerance 1e-4
    set->ccd.support1 = ccdSupport;
    set->ccd.support2 = ccdSupport;
    set->ccd.center1 = ccdCenter;
    set->ccd.center2 = ccdCenter;
    set->ccd.max_iterations = 1000;  // default is unbounded: cap it so a bad pair cannot hang the bench
    return set;
}
#endif

#if CDLAB_HAVE_BULLET
struct BulletSet {
    std::vector<std::unique_ptr<btConvexHullShape>> a, b;
};

std::unique_ptr<btConvexHullShape> bulletHull(const std::vector<Vec3>& v) {
    auto hull = std::make_unique<btConvexHullShape>();
    for (const Vec3& x : v) hull->addPoint(btVector3(x.x(), x.y(), x.z()), false);
    hull->recalcLocalAabb();
    hull->setMargin(0.0);  // the exact polytope: no rounding margin
    return hull;
}

std::shared_ptr<BulletSet> makeBulletSet(const std::vector<PeerPair>& pairs) {
    auto set = std::make_shared<BulletSet>();
    for (const PeerPair& p : pairs) {
        set->a.push_back(bulletHull(*p.va));
        set->b.push_back(bulletHull(*p.vb));
    }
    return set;
}

// Collects Bullet's contact points: the deepest penetration (Bullet reports depth < 0 when
// penetrating) and the count.
struct DeepestPoint : btDiscreteCollisionDetectorInterface::Result {
    double deepest = 0.0;
    int points = 0;
    void setShapeIdentifiersA(int, int) override {}
    void setShapeIdentifiersB(int, int) override {}
    void addContactPoint(const btVector3&, const btVector3&, btScalar depth) override {
        ++points;
        deepest = std::max(deepest, -double(depth));
    }
};

btTransform bulletTransform(const Transform& t) {
    return btTransform(btQuaternion(t.rotation.x(), t.rotation.y(), t.rotation.z(), t.rotation.w()),
                       btVector3(t.position.x(), t.position.y(), t.position.z()));
}

// Shapes with their polyhedral features (faces, for the clipping), margin 0 (the exact body),
// and the clipping's vertex buffers, reused between calls as btConvexConvexAlgorithm does.
struct BulletContactSet {
    std::vector<std::unique_ptr<btPolyhedralConvexShape>> a, b;
    std::vector<btTransform> ta, tb;
    btVertexArray buffer1, buffer2;
};

std::unique_ptr<btPolyhedralConvexShape> bulletContactShape(const ContactPeerPair& p, bool first) {
    std::unique_ptr<btPolyhedralConvexShape> shape;
    const std::vector<Vec3>* hull = first ? p.hullA : p.hullB;
    if (hull) {
        auto h = std::make_unique<btConvexHullShape>();
        for (const Vec3& x : *hull) h->addPoint(btVector3(x.x(), x.y(), x.z()), false);
        h->recalcLocalAabb();
        shape = std::move(h);
    } else {
        const Vec3& e = first ? p.halfA : p.halfB;
        shape = std::make_unique<btBoxShape>(btVector3(e.x(), e.y(), e.z()));
    }
    shape->setMargin(0.0);  // btBoxShape keeps its outer extents: the same box
    shape->initializePolyhedralFeatures();
    return shape;
}

// Bullet's general path (btConvexConvexAlgorithm with polyhedral features): the separating axis
// over face normals and edge pairs, then the incident face clipped against the reference hull.
PeerAnswer bulletClipping(BulletContactSet& s, int i) {
    DeepestPoint out;
    btVector3 sep;
    const btConvexPolyhedron& pa = *s.a[i]->getConvexPolyhedron();
    const btConvexPolyhedron& pb = *s.b[i]->getConvexPolyhedron();
    if (btPolyhedralContactClipping::findSeparatingAxis(pa, pb, s.ta[i], s.tb[i], sep, out)) {
        s.buffer1.resize(0);
        s.buffer2.resize(0);
        btPolyhedralContactClipping::clipHullAgainstHull(sep, pa, pb, s.ta[i], s.tb[i], -1e30, 0.0, s.buffer1,
                                                         s.buffer2, out);
    }
    return PeerAnswer{out.deepest, out.points};
}

// Box–plane cases as Bullet's dispatcher holds them: collision objects, and per case one
// btConvexPlaneCollisionAlgorithm with its persistent manifold (from the dispatcher's pools).
struct BulletPlaneSet {
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher{&configuration};
    btDispatcherInfo info;
    std::vector<std::unique_ptr<btBoxShape>> boxes;
    std::vector<std::unique_ptr<btStaticPlaneShape>> planes;
    std::vector<std::unique_ptr<btCollisionObject>> boxObjects, planeObjects;
    std::vector<btCollisionAlgorithm*> algorithms;
    std::vector<btPersistentManifold*> manifolds;

    /// Case i's box and plane as the dispatcher hands them to an algorithm (views, not copies).
    struct Wrapped {
        btCollisionObjectWrapper box, plane;
        Wrapped(const BulletPlaneSet& s, std::size_t i)
            : box(nullptr, s.boxes[i].get(), s.boxObjects[i].get(), s.boxObjects[i]->getWorldTransform(), -1, -1),
              plane(nullptr, s.planes[i].get(), s.planeObjects[i].get(), s.planeObjects[i]->getWorldTransform(), -1,
                    -1) {}
    };

    BulletPlaneSet(const BulletPlaneSet&) = delete;
    BulletPlaneSet& operator=(const BulletPlaneSet&) = delete;
    BulletPlaneSet(const std::vector<PlanePeerCase>& cases, int perturbations, int minimumPoints) {
        btConvexPlaneCollisionAlgorithm::CreateFunc create;  // box first, plane second (not swapped)
        create.m_numPerturbationIterations = perturbations;
        create.m_minimumPointsPerturbationThreshold = minimumPoints;
        btManifoldArray owned;
        for (const PlanePeerCase& c : cases) {
            boxes.push_back(std::make_unique<btBoxShape>(btVector3(c.half.x(), c.half.y(), c.half.z())));
            boxes.back()->setMargin(0.0);  // btBoxShape keeps its outer extents: the same box
            planes.push_back(std::make_unique<btStaticPlaneShape>(btVector3(c.normal.x(), c.normal.y(), c.normal.z()),
                                                                  c.offset));
            boxObjects.push_back(std::make_unique<btCollisionObject>());
            boxObjects.back()->setCollisionShape(boxes.back().get());
            boxObjects.back()->setWorldTransform(bulletTransform(c.pose));
            planeObjects.push_back(std::make_unique<btCollisionObject>());
            planeObjects.back()->setCollisionShape(planes.back().get());
            const Wrapped w(*this, algorithms.size());
            btCollisionAlgorithmConstructionInfo ci;
            ci.m_dispatcher1 = &dispatcher;
            algorithms.push_back(create.CreateCollisionAlgorithm(ci, &w.box, &w.plane));
            owned.resize(0);
            algorithms.back()->getAllContactManifolds(owned);
            manifolds.push_back(owned.size() ? owned[0] : nullptr);
        }
    }
    ~BulletPlaneSet() {
        for (btCollisionAlgorithm* a : algorithms) {
            a->~btCollisionAlgorithm();  // releases its manifold to the dispatcher
            dispatcher.freeCollisionAlgorithm(a);
        }
    }

    PeerAnswer run(int i) {
        PeerAnswer answer;
        btPersistentManifold* manifold = manifolds[i];
        if (!manifold) return answer;  // the dispatcher declined the pair (needsCollision): never for these objects
        manifold->clearManifold();
        const Wrapped w(*this, static_cast<std::size_t>(i));
        btManifoldResult result(&w.box, &w.plane);
        result.setPersistentManifold(manifold);
        algorithms[i]->processCollision(&w.box, &w.plane, info, &result);
        answer.iterations = manifold->getNumContacts();
        for (int k = 0; k < answer.iterations; ++k)
            answer.value = std::max(answer.value, -double(manifold->getContactPoint(k).getDistance()));
        return answer;
    }
};
#endif

}  // namespace

std::vector<PeerRunner> makePeerRunners(const std::vector<PeerPair>& pairs, const std::string& query) {
    std::vector<PeerRunner> runners;
#if CDLAB_HAVE_CCD
    {
        auto set = makeCcdSet(pairs);
        if (query == "gjk_intersect") {
            runners.push_back({"libccd GJK", [set](int i) {
                                   return PeerAnswer{ccdGJKIntersect(&set->a[i], &set->b[i], &set->ccd) ? 1.0 : 0.0, 0};
                               }});
            runners.push_back({"libccd MPR", [set](int i) {
                                   return PeerAnswer{ccdMPRIntersect(&set->a[i], &set->b[i], &set->ccd) ? 1.0 : 0.0, 0};
                               }});
        } else if (query == "epa_depth") {
            runners.push_back({"libccd GJK+EPA", [set](int i) {
                                   ccd_real_t depth = 0;
                                   ccd_vec3_t dir, pos;
                                   const int r =
                                       ccdGJKPenetration(&set->a[i], &set->b[i], &set->ccd, &depth, &dir, &pos);
                                   return PeerAnswer{r == 0 ? double(depth) : 0.0, 0};
                               }});
            runners.push_back({"libccd MPR", [set](int i) {
                                   ccd_real_t depth = 0;
                                   ccd_vec3_t dir, pos;
                                   const int r =
                                       ccdMPRPenetration(&set->a[i], &set->b[i], &set->ccd, &depth, &dir, &pos);
                                   return PeerAnswer{r == 0 ? double(depth) : 0.0, 0};
                               }});
        }
    }
#endif
#if CDLAB_HAVE_BULLET
    {
        auto set = makeBulletSet(pairs);
        const btTransform identity = btTransform::getIdentity();
        if (query == "gjk_distance") {
            runners.push_back({"Bullet GJK (double)", [set, identity](int i) {
                                   btGjkEpaSolver2::sResults r;
                                   btGjkEpaSolver2::Distance(set->a[i].get(), identity, set->b[i].get(), identity,
                                                             btVector3(1, 0, 0), r);
                                   return PeerAnswer{double(r.distance), 0};
                               }});
        } else if (query == "epa_depth") {
            runners.push_back({"Bullet GJK+EPA (double)", [set, identity](int i) {
                                   btGjkEpaSolver2::sResults r;
                                   const bool hit = btGjkEpaSolver2::Penetration(
                                       set->a[i].get(), identity, set->b[i].get(), identity, btVector3(1, 0, 0), r);
                                   return PeerAnswer{hit ? -double(r.distance) : 0.0, 0};  // distance = -depth
                               }});
        }
    }
#endif
    (void)pairs;
    (void)query;
    return runners;
}

std::vector<PeerRunner> makeContactPeerRunners(const std::vector<ContactPeerPair>& pairs, const std::string& query) {
    std::vector<PeerRunner> runners;
#if CDLAB_HAVE_BULLET
    auto set = std::make_shared<BulletContactSet>();
    for (const ContactPeerPair& p : pairs) {
        set->a.push_back(bulletContactShape(p, true));
        set->b.push_back(bulletContactShape(p, false));
        set->ta.push_back(bulletTransform(p.ta));
        set->tb.push_back(bulletTransform(p.tb));
    }
    if (query == "box_box") {
        runners.push_back({"Bullet btBoxBoxDetector", [set](int i) {
                               btBoxBoxDetector detector(static_cast<const btBoxShape*>(set->a[i].get()),
                                                         static_cast<const btBoxShape*>(set->b[i].get()));
                               btDiscreteCollisionDetectorInterface::ClosestPointInput input;
                               input.m_transformA = set->ta[i];
                               input.m_transformB = set->tb[i];
                               DeepestPoint out;
                               detector.getClosestPoints(input, out, nullptr);
                               return PeerAnswer{out.deepest, out.points};
                           }});
    }
    if (query == "box_box" || query == "hull_hull")
        runners.push_back({"Bullet hull clipping", [set](int i) { return bulletClipping(*set, i); }});
#endif
    (void)pairs;
    (void)query;
    return runners;
}

std::vector<PeerRunner> makePlanePeerRunners(const std::vector<PlanePeerCase>& cases) {
    std::vector<PeerRunner> runners;
#if CDLAB_HAVE_BULLET
    auto single = std::make_shared<BulletPlaneSet>(cases, 1, 0);  // Bullet's defaults: no perturbation
    auto multi = std::make_shared<BulletPlaneSet>(cases, 3, 3);
    runners.push_back({"Bullet convex-plane, one point", [single](int i) { return single->run(i); }});
    runners.push_back({"Bullet convex-plane, multipoint", [multi](int i) { return multi->run(i); }});
#endif
    (void)cases;
    return runners;
}

#if CDLAB_HAVE_BULLET
namespace {

double threadMs() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// The world with its collision detection timed: btDiscreteDynamicsWorld::internalSingleStepSimulation
// calls this virtual once per step (AABB update, broad phase, narrow phase).
class TimedWorld : public btDiscreteDynamicsWorld {
public:
    using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;
    double collideMs = 0.0;
    void performDiscreteCollisionDetection() override {
        const double t0 = threadMs();
        btDiscreteDynamicsWorld::performDiscreteCollisionDetection();
        collideMs += threadMs() - t0;
    }
};

}  // namespace
#endif

std::unique_ptr<PeerWorld> makeBulletWorld(const std::vector<PeerWorldBody>& bodies, double timeStep, int iterations,
                                           const Vec3& gravity) {
#if CDLAB_HAVE_BULLET
    struct State {
        btDefaultCollisionConfiguration configuration;
        btCollisionDispatcher dispatcher{&configuration};
        btDbvtBroadphase broadphase;
        btSequentialImpulseConstraintSolver solver;
        TimedWorld world{&dispatcher, &broadphase, &solver, &configuration};
        std::vector<std::unique_ptr<btCollisionShape>> shapes;
        std::vector<std::unique_ptr<btRigidBody>> bodies;
        ~State() {
            for (auto& b : bodies) world.removeRigidBody(b.get());
        }
    };
    auto state = std::make_shared<State>();
    const auto v = [](const Vec3& x) { return btVector3(x.x(), x.y(), x.z()); };
    state->world.setGravity(v(gravity));
    state->world.getSolverInfo().m_numIterations = iterations;
    for (const PeerWorldBody& b : bodies) {
        std::unique_ptr<btCollisionShape> shape;
        switch (b.kind) {
            case PeerWorldBody::Kind::Box: {
                auto box = std::make_unique<btBoxShape>(v(b.half));
                box->initializePolyhedralFeatures();
                shape = std::move(box);
                break;
            }
            case PeerWorldBody::Kind::Hull: {
                auto hull = std::make_unique<btConvexHullShape>();
                for (const Vec3& p : *b.hull) hull->addPoint(v(p), false);
                hull->recalcLocalAabb();
                hull->setMargin(0.001);
                hull->initializePolyhedralFeatures();
                shape = std::move(hull);
                break;
            }
            case PeerWorldBody::Kind::Sphere: shape = std::make_unique<btSphereShape>(b.radius); break;
            case PeerWorldBody::Kind::Capsule: shape = std::make_unique<btCapsuleShape>(b.radius, 2 * b.halfHeight); break;
            case PeerWorldBody::Kind::Plane:
                shape = std::make_unique<btStaticPlaneShape>(v(b.planeNormal), b.planeOffset);
                break;
        }
        btTransform t;
        t.setOrigin(v(b.pose.position));
        t.setRotation(btQuaternion(b.pose.rotation.x(), b.pose.rotation.y(), b.pose.rotation.z(), b.pose.rotation.w()));
        const double mass = b.isStatic ? 0.0 : b.mass;
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape.get(),
                                                      b.isStatic ? btVector3(0, 0, 0) : v(b.inertiaDiagonal));
        info.m_startWorldTransform = t;
        info.m_friction = std::sqrt(b.friction);
        info.m_restitution = b.restitution;
        auto body = std::make_unique<btRigidBody>(info);
        body->setActivationState(DISABLE_DEACTIVATION);
        state->world.addRigidBody(body.get());
        state->shapes.push_back(std::move(shape));
        state->bodies.push_back(std::move(body));
    }
    auto peer = std::make_unique<PeerWorld>();
    peer->method = "Bullet btDiscreteDynamicsWorld";
    peer->step = [state, timeStep](double& collideMs) {
        state->world.collideMs = 0.0;
        const double t0 = threadMs();
        state->world.stepSimulation(timeStep, 0, timeStep);
        const double total = threadMs() - t0;
        collideMs = state->world.collideMs;
        return total;
    };
    peer->contactPoints = [state] {
        int n = 0;
        for (int i = 0; i < state->dispatcher.getNumManifolds(); ++i)
            n += state->dispatcher.getManifoldByIndexInternal(i)->getNumContacts();
        return n;
    };
    peer->pairs = [state] { return state->broadphase.getOverlappingPairCache()->getNumOverlappingPairs(); };
    peer->deepest = [state] {
        double d = 0.0;
        for (int i = 0; i < state->dispatcher.getNumManifolds(); ++i) {
            const btPersistentManifold* m = state->dispatcher.getManifoldByIndexInternal(i);
            for (int k = 0; k < m->getNumContacts(); ++k) d = std::max(d, -double(m->getContactPoint(k).getDistance()));
        }
        return d;
    };
    return peer;
#else
    (void)bodies, (void)timeStep, (void)iterations, (void)gravity;
    return nullptr;
#endif
}

std::unique_ptr<PeerBroadPhase> makeBulletDbvtBroadPhase() {
#if CDLAB_HAVE_BULLET
    // Objects enter on the first frame; each later frame moves every proxy (setAabb skips the tree
    // work when the box stays inside its fattened one) and collects the pairs. No dispatcher: the
    // pairs carry no collision algorithms to free.
    struct State {
        btDbvtBroadphase broadphase;
        std::vector<btBroadphaseProxy*> proxies;
        ~State() {
            for (btBroadphaseProxy* p : proxies) broadphase.destroyProxy(p, nullptr);
        }
    };
    auto state = std::make_shared<State>();
    auto peer = std::make_unique<PeerBroadPhase>();
    peer->method = "Bullet btDbvtBroadphase";
    peer->frame = [state](const std::vector<Aabb>& boxes) -> std::int64_t {
        const auto v = [](const Vec3& x) { return btVector3(x.x(), x.y(), x.z()); };
        if (state->proxies.empty()) {
            for (std::size_t i = 0; i < boxes.size(); ++i)
                state->proxies.push_back(state->broadphase.createProxy(
                    v(boxes[i].min), v(boxes[i].max), BOX_SHAPE_PROXYTYPE, reinterpret_cast<void*>(i + 1),
                    int(btBroadphaseProxy::DefaultFilter), int(btBroadphaseProxy::AllFilter), nullptr));
        } else {
            for (std::size_t i = 0; i < boxes.size(); ++i)
                state->broadphase.setAabb(state->proxies[i], v(boxes[i].min), v(boxes[i].max), nullptr);
        }
        state->broadphase.calculateOverlappingPairs(nullptr);
        return state->broadphase.getOverlappingPairCache()->getNumOverlappingPairs();
    };
    return peer;
#else
    return nullptr;
#endif
}

}  // namespace cdlab::demos
