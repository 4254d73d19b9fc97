#include "common/base/output_path.h"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "common/base/cli.h"

namespace ffriga {

namespace fs = std::filesystem;

void checkOutputWritable(const std::string& output, const std::string& option) {
  std::error_code ec;
  const fs::path p(output);
  if (output.empty()) throw UsageError(Str() << "option " << option << " needs a file name");
  if (fs::is_directory(p, ec)) {
    throw UsageError(Str() << option << " " << output << ": is a folder, expected a file name");
  }
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::exists(dir, ec)) {
    throw UsageError(Str() << option << " " << output << ": the folder '" << dir.string()
                           << "' does not exist");
  }
  if (!fs::is_directory(dir, ec)) {
    throw UsageError(Str() << option << " " << output << ": '" << dir.string()
                           << "' is not a folder");
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw UsageError(Str() << option << " " << output << ": the folder '" << dir.string()
                           << "' is not writable");
  }
  if (fs::exists(p, ec) && ::access(p.c_str(), W_OK) != 0) {
    throw UsageError(Str() << option << " " << output << ": the file exists and is not writable");
  }
}

void refuseInputAsOutput(const std::string& output, const std::string& option,
                         const std::string& input, const std::string& what) {
  std::error_code ec;
  if (!fs::exists(output, ec) || !fs::exists(input, ec)) return;
  if (fs::equivalent(output, input, ec) && !ec) {
    throw UsageError(Str() << option << " " << output << " is " << what << " (" << input
                           << "), an input of this run: refusing to overwrite it");
  }
}

}  // namespace ffriga
