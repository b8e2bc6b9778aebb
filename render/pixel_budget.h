// A cap on the pixels one scene's frames may take, whatever the demo drawing them declared: every
// Canvas::readPixels() on this thread counts its rendered (supersampled) pixels against the budget
// in force and throws ImageError before reading back the frame that would pass it. The harness
// opens one budget around each scene's run (hostile_harness_test "a scene's frames are bounded
// together"); without one, nothing is counted.
#pragma once

namespace cdlab::render {

class PixelBudget {
public:
    /// `limit`: the rendered pixels allowed on this thread while this object lives.
    explicit PixelBudget(double limit);
    ~PixelBudget();
    PixelBudget(const PixelBudget&) = delete;
    PixelBudget& operator=(const PixelBudget&) = delete;

    /// Counts `pixels` against the innermost budget of this thread (if any); throws ImageError
    /// naming the limit when they do not fit.
    static void spend(double pixels);

private:
    double limit_, used_ = 0;
    PixelBudget* outer_;
};

}  // namespace cdlab::render
