// casting.md: the steps from an export's files to a cast part (print, prepare, assemble, mix, pour,
// cure, demould), written from the export's manifest so that the two always agree.
#pragma once

#include <string>

#include "formats/json_out.h"

namespace app {

std::string CastingSheet(const Json& manifest);

}  // namespace app
