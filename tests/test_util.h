// Helpers shared by the tests: scene paths and small RIB fixtures.
#pragma once

#include <string>

namespace streyes::test {

// Absolute path of a file in the source tree, e.g. sourcePath("scenes/ramp.rib").
std::string sourcePath(const std::string& relative);

// A fresh, empty temporary directory for one test (removed at process exit is not guaranteed).
std::string makeTempDir(const std::string& tag);

}  // namespace streyes::test
