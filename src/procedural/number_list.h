// Comma-separated numbers of a built-in procedural's key=value parameter (area=X,Z, rect=..., a
// colour): the forest, the grass and the Weber-Penn trees read their lists the same way.
#pragma once

#include <string>
#include <vector>

#include "streyes/error.h"

namespace streyes {

// The n finite numbers of `value` ("1,2.5,3"); anything else is an InputError at `loc` naming
// `who` (the procedural: "forest", "grass", "tree"), the key and what it takes.
std::vector<double> parseNumberList(const char* who, const std::string& key, const std::string& value, size_t n,
                                    const SourceLoc& loc);

}  // namespace streyes
