// Output paths are checked before any work (issue 13): an output that resolves to one of the
// run's inputs (the same file, also through a link or another spelling of the path) is
// refused, and the output's folder must exist and be writable. Both throw UsageError (exit
// code 2) naming the option, the path and why.
#pragma once

#include <string>

namespace ffriga {

// The folder of `output` exists and is writable; `output` itself is not a folder and, if it
// exists, is writable. `option` names the command-line option (e.g. "-o").
void checkOutputWritable(const std::string& output, const std::string& option);

// Refuses `output` if it is the same file as `input` (`what` says which input, e.g. "the
// scene file"). Nothing to check while either does not exist.
void refuseInputAsOutput(const std::string& output, const std::string& option,
                         const std::string& input, const std::string& what);

}  // namespace ffriga
