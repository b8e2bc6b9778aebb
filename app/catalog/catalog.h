// The catalogue: every demo, and scene loading — the one place that knows every demo. A scene
// names its demo with its "demo" key; loading hands it to that demo's prepare().
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/scene/demo.h"

namespace cdlab::demos {

/// Every demo, in a fixed order.
const std::vector<const Demo*>& allDemos();
const Demo* findDemo(const std::string& name);

/// Loads a scene file and hands it to its demo (named by the "demo" key). Throws InputError.
std::unique_ptr<PreparedScene> loadScene(const std::string& file);
/// The same for scene text already in memory; `source` names it in error messages.
std::unique_ptr<PreparedScene> loadSceneText(const std::string& text, const std::string& source);
/// The same for parsed JSON.
std::unique_ptr<PreparedScene> prepareScene(const Json& json, const std::string& file);

}  // namespace cdlab::demos
