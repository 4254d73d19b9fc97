// Command-line plumbing shared by igaprep and ffrsim: the common options and the mapping
// from exceptions to exit codes (DESIGN.md, "Contracts"):
//   0 success, 2 bad input or usage (InputError, UsageError), 1 failure while computing.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "common/base/error.h"

namespace ffriga {

class UsageError : public InputError {
 public:
  explicit UsageError(const std::string& message) : InputError(message) {}
};

struct CommandLineConfig {
  bool help = false;
  bool version = false;
  int verbosity = 1;  // 0 with -q, 2 with -v
  int threads = 0;    // 0: OpenMP default
  std::vector<std::string> positional;
  std::string output;  // -o FILE
  std::vector<std::string> sets;  // --set KEY=VALUE, in order (common/input/yaml_overrides.h)
};

// Parses argv. Unknown options and missing values throw UsageError. `extra` may consume a
// program-specific option: called with (argv, i), it returns how many arguments it used
// (0 if the option is not its own).
CommandLineConfig parseCommonOptions(int argc, char** argv,
                                     const std::function<int(char**, int, int)>& extra = {});

// Runs `body`, prints any error as "PROGRAM: error: MESSAGE" on stderr and returns the exit
// code. Applies --threads to OpenMP.
int runProgram(const std::string& program, const std::function<int()>& body);

// Applies --threads N (N > 0) to OpenMP.
void applyThreads(int threads);

// --help prints `usage`, --version the program's version line (both on stdout); true if
// one of them was given (the program then exits with 0).
bool printHelpOrVersion(const CommandLineConfig& o, const std::string& program, const char* usage);

}  // namespace ffriga
