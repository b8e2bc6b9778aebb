// Uniform grid broad phase (Ericson, Real-Time Collision Detection §7.1; hashed storage §7.1.3,
// Teschner et al., "Optimized Spatial Hashing for Collision Detection of Deformable Objects",
// VMV 2003): space is cut into cubes of side h, each box is entered into every cell its closed
// extent touches, and only boxes sharing a cell are tested (testAabbAabb semantics: touching
// counts). Cells live in a hash table rebuilt per frame with a counting sort by bucket (O(n +
// cells + tests), no per-frame allocation once the buffers have grown; at most one bucket per entry,
// each entry hashed once).
//
// Exactly-once rule: two overlapping boxes share every cell of their intersection box; the pair
// is reported only in the cell that holds the intersection's min corner (max of the two mins on
// each axis). That corner's cell index is computed by the same floor(x / h) as the boxes' cell
// ranges, so it is always one of the shared cells (no rounding can disagree).
// Hash collisions (two cells in one bucket) only cost tests: entries are compared by their exact
// integer cell coordinates.
//
// Good h: about the size of the typical box (each box then touches <= 8 cells). Boxes much larger
// than h touch many cells: build() refuses more than maxCellsPerBox for one box.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/broadphase/box_pair.h"

namespace cdlab {

enum class GridStatus {
    Ok,
    NonFiniteBox,  ///< a box has a NaN / inf coordinate (object says which)
    EmptyBox,      ///< a box has min > max on some axis
    BadCellSize,   ///< cellSize is not finite and > 0
    TooManyCells,  ///< a box touches more than maxCellsPerBox cells, or its cell index exceeds 2^53
};

struct UniformGridOptions {
    double cellSize = 1.0;  ///< h, world units
    std::int64_t maxCellsPerBox = 1 << 16;
};

struct UniformGridResult {
    GridStatus status = GridStatus::Ok;
    int object = -1;             ///< offending box when status is a box error
    std::int64_t entries = 0;    ///< (cell, box) entries, = sum over boxes of cells touched
    std::int64_t pairTests = 0;  ///< box pairs examined in shared buckets
    int pairs = 0;
};

class UniformGrid {
public:
    /// Rebuilds the grid over boxes[0..n) and collects the overlapping pairs (ids = indices).
    UniformGridResult build(const std::vector<Aabb>& boxes, const UniformGridOptions& options);
    /// Pairs of the last successful build (a < b), each once, in no particular order.
    const std::vector<BoxPair>& pairs() const { return pairs_; }

    /// Integer cell coordinates floor(p / h) of a point (finite p / h below 2^53).
    static std::array<std::int64_t, 3> cellOf(const Vec3& p, double h);

    /// One cell a segment passes through and the parameter t in [0, 1] where it enters it.
    struct RayCell {
        std::array<std::int64_t, 3> cell;
        double tEnter = 0.0;
    };
    /// The cells of side h the segment p + t (q − p), t in [0, 1], passes through, in order: the
    /// 3D DDA of Amanatides and Woo ("A Fast Voxel Traversal Algorithm", Eurographics 1987; Ericson
    /// §7.4.2), one step per cell boundary crossed (at a crossing of two boundaries at once, one
    /// axis after the other, so the cell between them is listed with its entry t). At most
    /// maxCells cells (a longer walk is cut there); non-finite input or h <= 0 gives none.
    static std::vector<RayCell> cellsAlongSegment(const Vec3& p, const Vec3& q, double h, int maxCells);

private:
    struct Entry {
        std::array<std::int64_t, 3> cell;
        int box;
        std::uint32_t bucket;  ///< hash of cell, masked to the table (32 bytes in all, as without it)
    };
    std::vector<Entry> entries_, sorted_;
    std::vector<std::uint32_t> bucketStart_;
    std::vector<BoxPair> pairs_;
};

}  // namespace cdlab
