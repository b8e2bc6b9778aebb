// The error a scene text or file gives when it is prepared ("" when it prepares): the demo tests'
// check that bad input is one error naming its JSON path.
#pragma once

#include <string>

#include "app/catalog/catalog.h"
#include "app/scene/json_reader.h"

namespace cdlab::test {

inline std::string sceneTextError(const std::string& text, const std::string& source = "scene.json") {
    try {
        demos::loadSceneText(text, source);
    } catch (const demos::InputError& e) {
        return e.what();
    }
    return "";
}

inline std::string sceneFileError(const std::string& file) {
    try {
        demos::loadScene(file);
    } catch (const demos::InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace cdlab::test
