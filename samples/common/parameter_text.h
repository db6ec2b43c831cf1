// Command-line text to a library parameter, shared by the samples: a float parameter takes any
// number, an int parameter a whole one, and the library checks the range.
#pragma once

#include <string>

#include "raps.h"

namespace raps_samples {

// Sets `param` from `text`, the value given to `flag`. Returns "" on success, else the message
// of a usage error (not a number, not whole, or the library's own message naming the range).
std::string set_parameter_from_text(raps_settings* settings, raps_param param,
                                    const std::string& flag, const std::string& text);

}  // namespace raps_samples
