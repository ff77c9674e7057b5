// `streyes farm status` and `streyes farm gather` (farm_report.cpp), dispatched by `streyes farm`
// (farm_command.cpp).
#pragma once

#include <string>
#include <vector>

namespace streyes::cli {

int farmStatus(const std::vector<std::string>& args);
int farmGather(const std::vector<std::string>& args);

}  // namespace streyes::cli
