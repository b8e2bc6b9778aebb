// One EGL context per test program for the tests that draw (created on first use, kept to exit):
// canvases are cheap, contexts are not.
#pragma once

#include <memory>

#include "render/gl_context.h"

namespace cdlab::test {

inline render::GlContext& glContext() {
    static std::unique_ptr<render::GlContext> context = render::GlContext::create();
    return *context;
}

}  // namespace cdlab::test
