#include "common/base/cli.h"

#include <cstring>
#include <iostream>

#include <omp.h>

#include "common/base/provenance.h"

namespace ffriga {

CommandLineConfig parseCommonOptions(int argc, char** argv,
                                     const std::function<int(char**, int, int)>& extra) {
  CommandLineConfig o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* name) -> std::string {
      if (i + 1 >= argc) throw UsageError(Str() << "option " << name << " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      o.help = true;
    } else if (a == "--version") {
      o.version = true;
    } else if (a == "-q" || a == "--quiet") {
      o.verbosity = 0;
    } else if (a == "-v" || a == "--verbose") {
      o.verbosity = 2;
    } else if (a == "-o" || a == "--output") {
      o.output = value("-o");
    } else if (a == "--set") {
      o.sets.push_back(value("--set"));
    } else if (a == "--threads") {
      const std::string v = value("--threads");
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || n < 1 || n > 1024) {
        throw UsageError(Str() << "--threads expects a positive integer, found '" << v << "'");
      }
      o.threads = static_cast<int>(n);
    } else if (extra) {
      const int used = extra(argv, i, argc);
      if (used > 0) {
        i += used - 1;
      } else if (!a.empty() && a[0] == '-' && a != "-") {
        throw UsageError(Str() << "unknown option '" << a << "' (see --help)");
      } else {
        o.positional.push_back(a);
      }
    } else if (!a.empty() && a[0] == '-' && a != "-") {
      throw UsageError(Str() << "unknown option '" << a << "' (see --help)");
    } else {
      o.positional.push_back(a);
    }
  }
  return o;
}

void applyThreads(int threads) {
  if (threads > 0) omp_set_num_threads(threads);
}

int runProgram(const std::string& program, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 2;
  } catch (const ComputeError& e) {
    std::cerr << program << ": computation failed: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << program << ": internal error: " << e.what() << "\n";
    return 1;
  }
}

bool printHelpOrVersion(const CommandLineConfig& o, const std::string& program, const char* usage) {
  if (o.help) {
    std::cout << usage;
    return true;
  }
  if (o.version) {
    std::cout << versionLine(program) << "\n";
    return true;
  }
  return false;
}

}  // namespace ffriga
