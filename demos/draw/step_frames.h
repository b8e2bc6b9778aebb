// Step frames of the stepping demos: which steps get a frame, their names, and the animated GIF.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "app/scene/demo.h"

namespace cdlab::demos {

/// Which of n steps get a frame when at most `maxFrames` may be drawn: the first maxFrames - 1
/// and the last (all when n <= maxFrames).
std::vector<int> framedSteps(int n, int maxFrames);

/// "step_03".
std::string stepFrameName(int i);

/// The animated GIF of the step frames (render/gif_writer.h), appended to out.files as
/// "animation.gif"; frames are box-downsampled by `downscale`.
void addGif(DemoOutput& out, const std::vector<const Frame*>& frames, int downscale);

/// What the step frames of a run of `iterations` iterations show, for a sheet's title, from the
/// 0-based indices `framed` that got a frame (iterations numbered from `first`): "one frame per
/// iteration", "iterations 4–6 not shown" (each run of skipped ones), or "no iteration ran";
/// `noun` names them ("step": the feature walks number their steps from 0).
/// Test: tests/demos/draw/step_frames_test.cpp.
std::string iterationCoverage(int iterations, const std::vector<int>& framed, const std::string& noun = "iteration",
                              int first = 1);

/// The end of a run that draws a frame per framed iteration (gjk, epa): the GIF of every frame so
/// far when `gif`, and with --steps a contact sheet of them titled "<scene title>: <algorithm>,
/// <iterationCoverage(iterations, framed)>".
void addAnimationAndSheet(render::GlContext& gl, const SceneCommon& common, const RunContext& ctx, bool gif,
                          const std::string& algorithm, int iterations, const std::vector<int>& framed,
                          DemoOutput& out);

/// One frame per query point, draw(i) for i in [0, count), then a contact sheet of them titled
/// "<scene title>: one query point per frame" (the voronoi_triangle scenes' steps).
void addQueryFramesAndSheet(render::GlContext& gl, const SceneCommon& common, int count,
                            const std::function<Frame(int)>& draw, DemoOutput& out);

}  // namespace cdlab::demos
