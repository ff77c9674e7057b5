// Reading scenes from RIB (RenderMan Interface Bytestream, ASCII), the subset in
// docs/SCENE-FORMAT.md. Malformed input throws InputError naming file:line; requests outside
// the subset warn once through the Log and are skipped.
#pragma once

#include <string>

#include "streyes/scene.h"

namespace streyes {

Scene parseRibFile(const std::string& path, Log& log);
Scene parseRibString(const std::string& text, const std::string& sourceName, Log& log);

}  // namespace streyes
