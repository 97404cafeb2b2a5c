#pragma once
#include <string>
#include <vector>

namespace octrace::cli {
// Each returns the process exit code; they throw octrace::Error subclasses for failures,
// which main() maps to exit codes (UsageError -> 2, the rest -> 1).
int runRender(const std::vector<std::string>& args);
int runInfo(const std::vector<std::string>& args);
int runSample(const std::vector<std::string>& args);
int runOptions(const std::vector<std::string>& args);
int runExport(const std::vector<std::string>& args);
int runBuild(const std::vector<std::string>& args);
int runCsg(const std::vector<std::string>& args);
int runSlice(const std::vector<std::string>& args);
int runAnimate(const std::vector<std::string>& args);
}  // namespace octrace::cli
