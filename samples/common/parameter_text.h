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

// A flag that sets one int parameter to 1 (--block-align, --keep-uv-seams, ...).
struct SwitchFlag {
    const char* flag;
    raps_param param;
    bool gltf;  // raps-gltf offers it too
};

// The flag's entry, or nullptr when `flag` is no switch.
const SwitchFlag* find_switch_flag(const std::string& flag);

// Sets the switch's parameter to 1. Returns "" on success, else the library's message.
std::string set_switch(raps_settings* settings, const SwitchFlag& flag);

// --max-size N: pages of at most N x N texels (with a density). Returns "" or a usage error.
std::string set_max_size(raps_settings* settings, const std::string& text);

// --lightmap: a lightmap's settings, the same in both tools. Padding 2 texels (Unity asks for at
// least 2), quarter turns only (texel rows stay texel rows), a mesh's charts on one page, and
// charts on whole texels (which a density gives, and which at a resolution whole texels ask
// for). Applied before the other flags are read, so that --padding and --rotate given too
// override these. Returns "" or the library's message.
std::string apply_lightmap_preset(raps_settings* settings);

// --stack or --stack-mirrored (`flag`): congruent charts share one place in the atlas. Refused
// with --lightmap, where every chart needs texels of its own. Returns "" or a usage error.
std::string set_stack(raps_settings* settings, const std::string& flag, bool lightmap);

// The name of the choice with `value` ("?" when there is none).
const char* choice_name(const ParameterFlag& flag, int64_t value);

// The name a report gives a progress phase ("initial_map", ...; "?" for an unknown one).
const char* phase_name(raps_phase phase);

}  // namespace raps_samples
