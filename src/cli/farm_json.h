// The farm's JSON files (the shot manifest, the tasks' --stats, the block-length curve) through
// nlohmann-json: members keep the order they were written in, and reading is forgiving where the
// files may be older than the code (a member absent reads as null, a number as its fallback).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace streyes::farm {

using Json = nlohmann::ordered_json;

// Parses `text`; std::runtime_error naming `what` (a file name), the line and column when it is
// not JSON.
Json parseJson(const std::string& text, const std::string& what);
// Reads and parses a file; std::runtime_error naming it when it cannot be read or parsed.
Json loadJson(const std::string& path);

// A member of an object; null when absent or when `j` is not an object.
const Json& member(const Json& j, const std::string& key);
// A number, or `fallback` when `j` is not one.
double num(const Json& j, double fallback = 0);
// A string, or "" when `j` is not one.
std::string str(const Json& j);
// Indented text (two spaces), members in order; ends without a newline. NaN and infinities are
// written as null.
std::string dumpJson(const Json& j);

}  // namespace streyes::farm
