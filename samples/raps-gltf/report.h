// The JSON raps-gltf prints (and writes with --report): per asset the settings, each baked
// group's charts, atlas size, utilization, distortion figures and times, each primitive's
// counts and what happened to its attributes, what was skipped and why, and the output's files.
#pragma once

#include <string>

#include "gltf_bake.h"
#include "gltf_load.h"
#include "gltf_output.h"
#include "raps.h"

namespace raps_gltf {

// JSON has no NaN or infinity: those become null.
Json json_number(double value);

Json settings_json(const raps_settings* settings, const BakeOptions& options);
Json bake_json(const BakeResult& bake);
Json output_json(const WriteReport& write);

}  // namespace raps_gltf
