// A path's extension in lower case, dot included (".obj", ".glb"; "" for none): how the readers
// pick a format, so "Scene.OBJ" reads like "scene.obj".
#pragma once

#include <string>

namespace radfarm {

std::string LowercaseExtension(const std::string& path);

}  // namespace radfarm
