#include "parameter_text.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace raps_samples {

std::string set_parameter_from_text(raps_settings* settings, raps_param param,
                                    const std::string& flag, const std::string& text) {
    char* end = nullptr;
    errno = 0;
    const double number = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || errno != 0) {
        return flag + " needs a number, not '" + text + "'";
    }
    int32_t is_float = 0;
    raps_param_info(param, nullptr, &is_float, nullptr, nullptr, nullptr);
    raps_status status;
    if (is_float) {
        status = raps_settings_set_float(settings, param, number);
    } else {
        if (number != std::floor(number) || std::fabs(number) > 9e18) {
            return flag + " needs a whole number, not '" + text + "'";
        }
        status = raps_settings_set_int(settings, param, static_cast<int64_t>(number));
    }
    if (status != RAPS_OK) return flag + ": " + raps_settings_last_error(settings);
    return "";
}

}  // namespace raps_samples
