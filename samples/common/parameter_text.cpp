#include "parameter_text.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace raps_samples {

namespace {

const std::vector<ParameterFlag> kParameterFlags = {
    {"--weights",
     RAPS_PARAM_WEIGHTS,
     true,
     {{"mvc", RAPS_WEIGHTS_MEAN_VALUE},
      {"cotan", RAPS_WEIGHTS_COTANGENT},
      {"uniform", RAPS_WEIGHTS_UNIFORM}}},
    {"--monitor",
     RAPS_PARAM_MONITOR,
     true,
     {{"none", RAPS_MONITOR_NONE},
      {"area", RAPS_MONITOR_AREA},
      {"length", RAPS_MONITOR_EDGE_LENGTH},
      {"angle", RAPS_MONITOR_ANGLE}}},
    {"--iteration-mode",
     RAPS_PARAM_ITERATION_MODE,
     true,
     {{"accumulate", RAPS_ITERATION_ACCUMULATE}, {"reapply", RAPS_ITERATION_REAPPLY}}},
    {"--boundary",
     RAPS_PARAM_BOUNDARY,
     false,
     {{"circle", RAPS_BOUNDARY_CIRCLE}, {"square", RAPS_BOUNDARY_SQUARE}}},
    {"--sphere-method",
     RAPS_PARAM_SPHERE_METHOD,
     false,
     {{"literal", RAPS_SPHERE_LITERAL}, {"robust", RAPS_SPHERE_ROBUST}}},
    {"--sphere-uv",
     RAPS_PARAM_SPHERE_UV,
     false,
     {{"none", RAPS_SPHERE_UV_NONE}, {"octahedral", RAPS_SPHERE_UV_OCTAHEDRAL}}},
    {"--alpha", RAPS_PARAM_ALPHA, true, {}},
    {"--iterations", RAPS_PARAM_ITERATIONS, true, {}},
    {"--max-triangles", RAPS_PARAM_MAX_TRIANGLES, true, {}},
    {"--max-memory-mb", RAPS_PARAM_MAX_MEMORY_MB, true, {}},
    {"--threads", RAPS_PARAM_THREADS, true, {}},
    {"--resolution", RAPS_PARAM_ATLAS_RESOLUTION, true, {}},
    {"--padding", RAPS_PARAM_ATLAS_PADDING, true, {}},
    {"--weld-tolerance", RAPS_PARAM_WELD_TOLERANCE, true, {}},
    {"--hard-edge-angle", RAPS_PARAM_HARD_EDGE_ANGLE, true, {}},
    {"--max-l2-stretch", RAPS_PARAM_ATLAS_MAX_L2_STRETCH, true, {}},
    {"--max-linf-stretch", RAPS_PARAM_ATLAS_MAX_LINF_STRETCH, true, {}},
    {"--texels-per-unit", RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, true, {}},
    {"--rotate",
     RAPS_PARAM_ATLAS_ROTATION,
     true,
     {{"any", RAPS_ROTATION_ANY},
      {"quarter", RAPS_ROTATION_QUARTER},
      {"none", RAPS_ROTATION_NONE}}},
    {"--margin", RAPS_PARAM_ATLAS_MARGIN, true, {}},
    {"--stack-tolerance", RAPS_PARAM_ATLAS_STACK_TOLERANCE, true, {}},
    {"--damping", RAPS_PARAM_SPHERE_DAMPING, false, {}},
    {"--tolerance", RAPS_PARAM_SPHERE_TOLERANCE, false, {}},
    {"--max-sweeps", RAPS_PARAM_SPHERE_MAX_SWEEPS, false, {}},
    {"--alpha-steps", RAPS_PARAM_SPHERE_ALPHA_STEPS, false, {}},
};

const SwitchFlag kSwitchFlags[] = {
    {"--block-align", RAPS_PARAM_ATLAS_BLOCK_ALIGN, true},
    {"--mesh-per-page", RAPS_PARAM_ATLAS_MESH_PER_PAGE, false},
    {"--whole-texels", RAPS_PARAM_ATLAS_WHOLE_TEXELS, false},
    {"--keep-uv-seams", RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS, true},
};

std::string library_error(raps_settings* settings, raps_status status) {
    return status == RAPS_OK ? std::string() : std::string(raps_settings_last_error(settings));
}

}  // namespace

const ParameterFlag* find_parameter_flag(const std::string& flag) {
    for (const ParameterFlag& entry : kParameterFlags) {
        if (flag == entry.flag) return &entry;
    }
    return nullptr;
}

std::string set_parameter_from_text(raps_settings* settings, const ParameterFlag& flag,
                                    const std::string& text) {
    const std::string name = flag.flag;
    raps_status status;
    if (!flag.choices.empty()) {
        const auto choice =
            std::find_if(flag.choices.begin(), flag.choices.end(),
                         [&](const std::pair<const char*, int64_t>& c) { return text == c.first; });
        if (choice == flag.choices.end()) return "unknown value '" + text + "' for " + name;
        status = raps_settings_set_int(settings, flag.param, choice->second);
    } else {
        char* end = nullptr;
        errno = 0;
        const double number = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || errno != 0) {
            return name + " needs a number, not '" + text + "'";
        }
        int32_t is_float = 0;
        raps_param_info(flag.param, nullptr, &is_float, nullptr, nullptr, nullptr);
        if (is_float) {
            status = raps_settings_set_float(settings, flag.param, number);
        } else {
            if (number != std::floor(number) || std::fabs(number) > 9e18) {
                return name + " needs a whole number, not '" + text + "'";
            }
            status = raps_settings_set_int(settings, flag.param, static_cast<int64_t>(number));
        }
    }
    if (status != RAPS_OK) return name + ": " + raps_settings_last_error(settings);
    return "";
}

const SwitchFlag* find_switch_flag(const std::string& flag) {
    for (const SwitchFlag& entry : kSwitchFlags) {
        if (flag == entry.flag) return &entry;
    }
    return nullptr;
}

std::string set_switch(raps_settings* settings, const SwitchFlag& flag) {
    return library_error(settings, raps_settings_set_int(settings, flag.param, 1));
}

std::string set_max_size(raps_settings* settings, const std::string& text) {
    for (raps_param side : {RAPS_PARAM_ATLAS_MAX_WIDTH, RAPS_PARAM_ATLAS_MAX_HEIGHT}) {
        const ParameterFlag entry{"--max-size", side, false, {}};
        const std::string error = set_parameter_from_text(settings, entry, text);
        if (!error.empty()) return error;
    }
    return "";
}

std::string apply_lightmap_preset(raps_settings* settings) {
    const std::pair<raps_param, int64_t> preset[] = {
        {RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS},
        {RAPS_PARAM_ATLAS_PADDING, 2},
        {RAPS_PARAM_ATLAS_ROTATION, RAPS_ROTATION_QUARTER},
        {RAPS_PARAM_ATLAS_MESH_PER_PAGE, 1},
        {RAPS_PARAM_ATLAS_WHOLE_TEXELS, 1}};
    for (const auto& p : preset) {
        const std::string error =
            library_error(settings, raps_settings_set_int(settings, p.first, p.second));
        if (!error.empty()) return error;
    }
    return "";
}

std::string set_stack(raps_settings* settings, const std::string& flag, bool lightmap) {
    if (lightmap) {
        return flag + " and --lightmap exclude each other: a lightmap needs every chart its own "
                      "texels";
    }
    const int64_t mode = flag == "--stack" ? RAPS_STACK_RIGID : RAPS_STACK_MIRRORED;
    const std::string error =
        library_error(settings, raps_settings_set_int(settings, RAPS_PARAM_ATLAS_STACK, mode));
    return error.empty() ? "" : flag + ": " + error;
}

const char* choice_name(const ParameterFlag& flag, int64_t value) {
    for (const auto& choice : flag.choices) {
        if (choice.second == value) return choice.first;
    }
    return "?";
}

const char* phase_name(raps_phase phase) {
    static const char* const kNames[RAPS_PHASE_COUNT] = {
        "validate", "topology", "initial_map", "adapt", "metrics", "segment", "pack"};
    return phase >= 0 && phase < RAPS_PHASE_COUNT ? kNames[phase] : "?";
}

}  // namespace raps_samples
