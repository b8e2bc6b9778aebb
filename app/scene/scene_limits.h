// What a scene file may ask for (docs/limits.md; docs/scenes.md names the limit of each key).
// Every quantity that multiplies the work or memory of a run has a limit here, checked in the demo's
// prepare() — before anything is computed, allocated or written — and past it the scene is one
// error naming the file, the JSON path and the limit.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "app/scene/json_reader.h"

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
/// Supersampled pixels of all the frames one scene draws (its views, per-step frames, plots and
/// contact sheet, each counted at its frame size): every frame is kept until the scene is written,
/// with a copy for the animation GIF, ~8 bytes a pixel in all (a 64-query voronoi_triangle scene
/// with steps, 2^28 pixels at 2048², took 1.87 GB). 2^27 takes 64 query frames at 1024² or 8 frames
/// at 4096²: ~1 GB of kept frames beside the 2.0 GB peak of drawing a 2^24-pixel one.
constexpr double kMaxScenePixels = double(1 << 27);

/// Characters (UTF-8 code points) of a scene's texts: every one is drawn or named on a frame, wrapped
/// to the frame's width, and a contact sheet grows with its caption (a 100 KB title took 2.8 GB and
/// 9-13 s; a 30 KB caption made a 1008 x 18678 sheet). The longest in the golden scenes: a title of
/// 88, a caption of 129, a label of 28. Any other string of a scene (a label, a mode) has
/// kMaxLabelChars; "_comment" is not drawn and has none.
constexpr std::size_t kMaxTitleChars = 200;
constexpr std::size_t kMaxCaptionChars = 1000;
constexpr std::size_t kMaxLabelChars = 100;

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
/// The density's lower bound keeps the smallest body a scene can give (a box of half extents 1e-5:
/// 8e-15 m³, principal moments ~5e-25 kg m² per unit density) at mass 8e-18 kg and moments
/// ~5e-28 kg m², whose inverse inertia tensor (through a determinant ~1e-83) is a normal double;
/// 1e-300 underflowed it and the run ended in a NaN. kMinMass and kMinInertia check the body itself
/// (a thin polytope has less than the box): far below the smallest box at kMinDensity, and far above
/// where the simulation's reciprocals overflow (~1e-308) or the tensor's determinant underflows
/// (principal moments ~1e-102).
constexpr double kMinDensity = 1e-3;
constexpr double kMinMass = 1e-30;
constexpr double kMinInertia = 1e-80;
constexpr double kMaxDensity = 1e6;
constexpr double kMaxSpeed = 1e3;
constexpr double kMaxGravity = 1e3;

/// Fails at the first string of the scene (any depth; "_comment" members skipped) longer than its
/// limit: $.title kMaxTitleChars, $.caption kMaxCaptionChars, any other kMaxLabelChars.
void requireTextLengths(const JsonNode& scene);

/// Reads [x, y, z] with every |coordinate| <= kMaxSceneCoordinate.
Vec3 sceneVec3(const JsonNode& node);
/// Reads [x, y] (z = 0) with the same limit.
Vec3 sceneVec2(const JsonNode& node);
/// A list of [x, y, z] with between minCount and maxCount entries.
std::vector<Vec3> sceneVec3List(const JsonNode& node, std::size_t minCount, std::size_t maxCount);
/// A list of [x, y] (z = 0) with between minCount and maxCount entries.
std::vector<Vec3> sceneVec2List(const JsonNode& node, std::size_t minCount, std::size_t maxCount);
/// A coordinate-like number: finite, |x| <= kMaxSceneCoordinate.
double sceneCoordinate(const JsonNode& node);
/// A size: in [kMinSceneSize, kMaxSceneCoordinate].
double sceneSize(const JsonNode& node);
/// Half extents / stretch factors: every component a size.
Vec3 sceneSizes(const JsonNode& node);

/// Fails at `node` when value > limit: "<what> is <value>, above the limit of <limit> (<why>)".
void requireAtMost(const JsonNode& node, double value, double limit, const std::string& what, const std::string& why);
/// Fails at `node` when value < limit: "<what> is <value>, below the limit of <limit> (<why>)".
void requireAtLeast(const JsonNode& node, double value, double limit, const std::string& what, const std::string& why);

}  // namespace cdlab::demos
