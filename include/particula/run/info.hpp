// `particula info CASE`: what a run would be (particles, dt, steps, memory, time) without
// running it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace particula {

int info_command(const std::filesystem::path& case_file, const std::vector<std::string>& overrides);

}  // namespace particula
