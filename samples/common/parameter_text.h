// Command-line text to library parameters, shared by the two command-line tools: one table of
// the flags that set a parameter, and their parsing. A float parameter takes any number, an int
// parameter a whole one or one of its named choices, and the library checks the range.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "raps.h"

namespace raps_samples {

// A flag that sets one parameter: to one of `choices` by name, or, when there are none, to a
// number.
struct ParameterFlag {
    const char* flag;
    raps_param param;
    bool atlas;  // an atlas parameter that raps-gltf offers (it offers only these)
    std::vector<std::pair<const char*, int64_t>> choices;
};

// The flag's entry, or nullptr when `flag` sets no parameter.
const ParameterFlag* find_parameter_flag(const std::string& flag);

// Sets the flag's parameter from `text`. Returns "" on success, else the message of a usage
// error (an unknown choice, not a number, not whole, or the library's message naming the range).
std::string set_parameter_from_text(raps_settings* settings, const ParameterFlag& flag,
                                    const std::string& text);

// The name of the choice with `value` ("?" when there is none).
const char* choice_name(const ParameterFlag& flag, int64_t value);

// The name a report gives a progress phase ("initial_map", ...; "?" for an unknown one).
const char* phase_name(raps_phase phase);

}  // namespace raps_samples
