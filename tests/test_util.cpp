#include "test_util.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace streyes::test {

std::string sourcePath(const std::string& relative) {
    return std::string(STREYES_SOURCE_DIR) + "/" + relative;
}

std::string makeTempDir(const std::string& tag) {
    std::string tmpl = (std::filesystem::temp_directory_path() / ("streyes-" + tag + "-XXXXXX")).string();
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed for " + tmpl);
    return tmpl;
}

}  // namespace streyes::test
