#include "app/catalog/catalog.h"

#include "demos/accuracy/accuracy_demo.h"
#include "demos/bounding_volumes/bounding_volumes_demo.h"
#include "demos/bvh/bvh_demo.h"
#include "demos/drop/drop_demo.h"
#include "demos/epa/epa_demo.h"
#include "demos/gjk/gjk_demo.h"
#include "demos/lin_canny/lin_canny_demo.h"
#include "demos/mtd_backtracking/mtd_backtracking_demo.h"
#include "demos/nonconvex/nonconvex_demo.h"
#include "demos/polyhedron_plane/polyhedron_plane_demo.h"
#include "demos/primitives/primitives_demo.h"
#include "demos/space_partition/space_partition_demo.h"
#include "demos/sweep_and_prune/sweep_and_prune_demo.h"
#include "demos/vclip/vclip_demo.h"
#include "demos/voronoi_triangle/voronoi_triangle_demo.h"
#include "demos/world/world_demo.h"

namespace cdlab::demos {

const std::vector<const Demo*>& allDemos() {
    static const std::vector<const Demo*> demos = {&voronoiDemo(),
                                                   &gjkDemo(),
                                                   &epaDemo(),
                                                   &vclipDemo(),
                                                   &linCannyDemo(),
                                                   &polyhedronPlaneDemo(),
                                                   &dropDemo(),
                                                   &accuracyDemo(),
                                                   &spacePartitionDemo(),
                                                   &boundingVolumesDemo(),
                                                   &bvhDemo(),
                                                   &sweepAndPruneDemo(),
                                                   &primitivesDemo(),
                                                   &mtdBacktrackingDemo(),
                                                   &nonconvexDemo(),
                                                   &worldDemo()};
    return demos;
}

const Demo* findDemo(const std::string& name) {
    for (const Demo* d : allDemos())
        if (d->name() == name) return d;
    return nullptr;
}

std::unique_ptr<PreparedScene> loadScene(const std::string& file) { return prepareScene(readJsonFile(file), file); }

std::unique_ptr<PreparedScene> loadSceneText(const std::string& text, const std::string& source) {
    return prepareScene(parseJson(text, source), source);
}

std::unique_ptr<PreparedScene> prepareScene(const Json& json, const std::string& file) {
    JsonNode root(json, "$", file);
    if (!root.isObject()) root.fail("a scene must be a JSON object, got " + JsonNode::describe(json));
    auto it = json.find("demo");
    if (it == json.end()) root.fail("missing required key 'demo'");
    JsonNode demoNode(*it, "$.demo", file);
    std::vector<std::string> names;
    for (const Demo* d : allDemos()) names.push_back(d->name());
    const Demo* demo = findDemo(demoNode.asEnum(names));
    return demo->prepare(json, file);
}

}  // namespace cdlab::demos
