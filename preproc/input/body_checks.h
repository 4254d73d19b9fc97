// The check phase of a body file (preproc/input/body_config.h): the values read against the
// geometry they build, each error naming the body file, the YAML line and the key (exit 2).
#pragma once

#include "preproc/input/body_config.h"

namespace ffriga {

// Checks `config` (read by readBodyConfig) in the order of the header comment of
// body_config.h; snaps the hierarchy's boxes and inverts the stress lines onto the patch.
// memory_limit_bytes: as for parseBodyConfig (0: this machine's physical memory).
void checkBodyConfig(BodyConfig& config, double memory_limit_bytes);

}  // namespace ffriga
