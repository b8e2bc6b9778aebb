// What a scene file may ask for (README, Hardening; docs/scenes.md names the limit of each key).
// Every quantity that multiplies the work or memory of a run has a limit here, checked in the demo's
// prepare() — before anything is computed, allocated or written — and past it the scene is one
// error naming the file, the JSON path and the limit.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "demos/scene/json_reader.h"

namespace cdlab::demos {

/// Largest |coordinate| of anything drawn. Figures are drawn in float32 (GL vertices): at 1e5 a float
/// is rounded to 0.008, so a unit-size body is still drawn within 1%; at 1e300 it is inf, and
/// everything derived from it (cameras, energies, traces) NaN.
constexpr double kMaxSceneCoordinate = 1e5;
/// Smallest positive size of a body (radius, half extent, major / minor radius, box size): the
/// same float32 argument at the other end (1e-5 of a unit-size view is below a pixel already).
constexpr double kMinSceneSize = 1e-5;

/// Image side in output pixels, and supersampled pixels per frame (width · height · scale²). A frame
/// costs ~118 bytes per supersampled pixel at its peak (colour and depth buffers, read-back,
/// downsampling, PNG encoding): a gjk scene at 2^24 pixels (4096², or 2048² at scale 2) took 9.3 s
/// and 2.0 GB on llvmpipe (2048²: 2.3 s, 0.6 GB); 8192² (2^26) took 146 s and 7.7 GB.
constexpr int kMaxImageSide = 4096;
constexpr double kMaxSupersampledPixels = double(1 << 24);

/// Vertices of one explicit polytope or polygon in a pair scene (gjk, epa), and vertices of A times
/// vertices of B: the configuration-space view draws the hull of all n·m differences. Two
/// 2000-vertex bodies (4·10^6 differences) took 18 s and 1.25 GB; 2.5·10^5 take well under a second.
constexpr std::size_t kMaxShapeVertices = 1000;
constexpr double kMaxMinkowskiPoints = 250000;

/// space_partition: grid cells over the region (one line per cell row and column is drawn; 10^4
/// cells is a 100 x 100 grid), explicit boxes / points / queries, and BSP polygon edges.
constexpr double kMaxGridCells = 1e4;
constexpr double kMaxPartitionItems = 2000;
constexpr double kMaxBspEdges = 256;

/// polyhedron_plane: vertices of one drawn face (a feature pair's face).
constexpr std::size_t kMaxFacePoints = 64;

/// voronoi_triangle: query points (one frame each with "steps").
constexpr std::size_t kMaxQueryPoints = 64;

/// drop: density (kg/m³), |velocity| (m/s) and |angular velocity| (rad/s), gravity (m/s²).
constexpr double kMaxDensity = 1e6;
constexpr double kMaxSpeed = 1e3;
constexpr double kMaxGravity = 1e3;

/// Reads [x, y, z] with every |coordinate| <= kMaxSceneCoordinate.
Vec3 sceneVec3(const JsonNode& node);
/// Reads [x, y] (z = 0) with the same limit.
Vec3 sceneVec2(const JsonNode& node);
/// A list of [x, y, z] with between minCount and maxCount entries.
std::vector<Vec3> sceneVec3List(const JsonNode& node, std::size_t minCount, std::size_t maxCount);
/// A coordinate-like number: finite, |x| <= kMaxSceneCoordinate.
double sceneCoordinate(const JsonNode& node);
/// A size: in [kMinSceneSize, kMaxSceneCoordinate].
double sceneSize(const JsonNode& node);
/// Half extents / stretch factors: every component a size.
Vec3 sceneSizes(const JsonNode& node);

/// Fails at `node` when value > limit: "<what> is <value>, above the limit of <limit> (<why>)".
void requireAtMost(const JsonNode& node, double value, double limit, const std::string& what, const std::string& why);

}  // namespace cdlab::demos
