#include "report_json.h"

#include <cmath>
#include <cstdio>

#include "parameter_text.h"

namespace param_report {
namespace {

const char* choice_name(const char* flag, int64_t value) {
    return raps_samples::choice_name(*raps_samples::find_parameter_flag(flag), value);
}

}  // namespace

std::string json_string(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buffer[8];
                    std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
                    out += buffer;
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

// JSON has no infinity or NaN: those become null, as in the project's reference metrics tool.
std::string json_number(double value) {
    if (!std::isfinite(value)) return "null";
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.10g", value);
    return buffer;
}

std::string settings_json(const raps_settings* settings) {
    int64_t domain, weights, monitor, iterations, mode, boundary, max_triangles, threads,
        resolution, padding, method, sphere_uv, max_sweeps, alpha_steps, max_width, max_height,
        rotation, margin, block_align, mesh_per_page, whole_texels, keep_uv_seams, repack, stack;
    double alpha, weld, hard_edge, max_l2, max_linf, damping, tolerance, texels_per_unit,
        stack_tolerance;
    raps_settings_get_int(settings, RAPS_PARAM_DOMAIN, &domain);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_RESOLUTION, &resolution);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_PADDING, &padding);
    raps_settings_get_float(settings, RAPS_PARAM_WELD_TOLERANCE, &weld);
    raps_settings_get_float(settings, RAPS_PARAM_HARD_EDGE_ANGLE, &hard_edge);
    raps_settings_get_float(settings, RAPS_PARAM_ATLAS_MAX_L2_STRETCH, &max_l2);
    raps_settings_get_float(settings, RAPS_PARAM_ATLAS_MAX_LINF_STRETCH, &max_linf);
    raps_settings_get_float(settings, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, &texels_per_unit);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_MAX_WIDTH, &max_width);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_MAX_HEIGHT, &max_height);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_ROTATION, &rotation);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_MARGIN, &margin);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_BLOCK_ALIGN, &block_align);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_MESH_PER_PAGE, &mesh_per_page);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_WHOLE_TEXELS, &whole_texels);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS, &keep_uv_seams);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_REPACK, &repack);
    raps_settings_get_int(settings, RAPS_PARAM_ATLAS_STACK, &stack);
    raps_settings_get_float(settings, RAPS_PARAM_ATLAS_STACK_TOLERANCE, &stack_tolerance);
    raps_settings_get_int(settings, RAPS_PARAM_WEIGHTS, &weights);
    raps_settings_get_int(settings, RAPS_PARAM_MONITOR, &monitor);
    raps_settings_get_int(settings, RAPS_PARAM_ITERATIONS, &iterations);
    raps_settings_get_int(settings, RAPS_PARAM_ITERATION_MODE, &mode);
    raps_settings_get_int(settings, RAPS_PARAM_BOUNDARY, &boundary);
    raps_settings_get_int(settings, RAPS_PARAM_MAX_TRIANGLES, &max_triangles);
    raps_settings_get_float(settings, RAPS_PARAM_ALPHA, &alpha);
    raps_settings_get_int(settings, RAPS_PARAM_THREADS, &threads);
    raps_settings_get_int(settings, RAPS_PARAM_SPHERE_METHOD, &method);
    raps_settings_get_int(settings, RAPS_PARAM_SPHERE_UV, &sphere_uv);
    raps_settings_get_int(settings, RAPS_PARAM_SPHERE_MAX_SWEEPS, &max_sweeps);
    raps_settings_get_int(settings, RAPS_PARAM_SPHERE_ALPHA_STEPS, &alpha_steps);
    raps_settings_get_float(settings, RAPS_PARAM_SPHERE_DAMPING, &damping);
    raps_settings_get_float(settings, RAPS_PARAM_SPHERE_TOLERANCE, &tolerance);

    const bool sphere = domain == RAPS_DOMAIN_SPHERE;
    const char* domain_name = domain == RAPS_DOMAIN_ATLAS ? "atlas" : sphere ? "sphere" : "disk";
    std::string json = std::string("{\"domain\": \"") + domain_name + "\", \"weights\": \"" +
                       choice_name("--weights", weights) + "\", \"monitor\": \"" +
                       choice_name("--monitor", monitor) + "\", \"alpha\": " + json_number(alpha) +
                       ", \"iterations\": " + std::to_string(iterations) +
                       ", \"iteration_mode\": \"" + choice_name("--iteration-mode", mode) +
                       "\", \"threads\": " + std::to_string(threads) +
                       ", \"max_triangles\": " + std::to_string(max_triangles);
    if (sphere) {
        json += std::string(", \"sphere_method\": \"") + choice_name("--sphere-method", method) +
                "\", \"sphere_uv\": \"" + choice_name("--sphere-uv", sphere_uv) +
                "\", \"damping\": " + json_number(damping) +
                ", \"tolerance\": " + json_number(tolerance) +
                ", \"max_sweeps\": " + std::to_string(max_sweeps) +
                ", \"alpha_steps\": " + std::to_string(alpha_steps);
    } else if (domain == RAPS_DOMAIN_ATLAS) {
        json += ", \"resolution\": " + std::to_string(resolution) +
                ", \"padding\": " + std::to_string(padding) +
                ", \"weld_tolerance\": " + json_number(weld) +
                ", \"hard_edge_angle\": " + json_number(hard_edge) +
                ", \"max_l2_stretch\": " + json_number(max_l2) +
                ", \"max_linf_stretch\": " + json_number(max_linf) +
                ", \"texels_per_unit\": " + json_number(texels_per_unit) +
                ", \"max_width\": " + std::to_string(max_width) +
                ", \"max_height\": " + std::to_string(max_height) + ", \"rotate\": \"" +
                choice_name("--rotate", rotation) + "\", \"margin\": " + std::to_string(margin) +
                ", \"block_align\": " + (block_align ? "true" : "false") +
                ", \"mesh_per_page\": " + (mesh_per_page ? "true" : "false") +
                ", \"whole_texels\": " + (whole_texels ? "true" : "false") +
                ", \"keep_uv_seams\": " + (keep_uv_seams ? "true" : "false") +
                ", \"repack\": " + (repack ? "true" : "false") + ", \"stack\": \"" +
                (stack == RAPS_STACK_NONE    ? "none"
                 : stack == RAPS_STACK_RIGID ? "rigid"
                                             : "mirrored") +
                "\", \"stack_tolerance\": " + json_number(stack_tolerance);
    } else {
        json += std::string(", \"boundary\": \"") + choice_name("--boundary", boundary) + "\"";
    }
    return json + "}";
}

std::string stats_json(const raps_stats& stats, bool atlas) {
    std::string json = "{\"flipped_triangles\": " + std::to_string(stats.flipped_triangles) +
                       ", \"zero_area_triangles\": " + std::to_string(stats.zero_area_triangles) +
                       ", \"negative_weights\": " + std::to_string(stats.negative_weights) +
                       ", \"adaptive_solves\": " + std::to_string(stats.adaptive_solves) +
                       ", \"relaxation_sweeps\": " + std::to_string(stats.relaxation_sweeps) +
                       ", \"area_log_mean\": " + json_number(stats.area_log_mean) +
                       ", \"area_max\": " + json_number(stats.area_max) +
                       ", \"angle_mean_deg\": " + json_number(stats.angle_mean_deg) +
                       ", \"angle_max_deg\": " + json_number(stats.angle_max_deg) +
                       ", \"stretch_l2\": " + json_number(stats.stretch_l2) +
                       ", \"stretch_linf\": " + json_number(stats.stretch_linf) +
                       ", \"charts\": " + std::to_string(stats.chart_count) +
                       ", \"atlas_width\": " + std::to_string(stats.atlas_width) +
                       ", \"atlas_height\": " + std::to_string(stats.atlas_height) +
                       ", \"utilization\": " + json_number(stats.utilization);
    if (atlas) {
        json += ", \"pages\": " + std::to_string(stats.page_count) +
                ", \"scaled_down_charts\": " + std::to_string(stats.scaled_down_charts) +
                ", \"texels_per_unit\": " + json_number(stats.texels_per_unit);
    }
    return json + "}";
}

std::string atlas_json(const std::vector<std::string>& paths, const std::vector<MeshShare>& shares,
                       const std::vector<raps_chart>& charts, const raps_stats& stats) {
    struct Sum {
        uint64_t charts = 0;
        double area_3d = 0, area_texels = 0;
    };
    std::vector<Sum> per_input(paths.size()), per_page(stats.page_count);
    for (const raps_chart& chart : charts) {
        // A stacked chart's texels are its original's: a page counts them once.
        const bool stacked = (chart.flags & RAPS_CHART_STACKED) != 0;
        for (Sum* sum : {&per_input[chart.mesh], &per_page[chart.page]}) {
            if (stacked && sum != &per_input[chart.mesh]) continue;
            ++sum->charts;
            sum->area_3d += chart.area_3d;
            sum->area_texels += chart.area_texels;
        }
    }
    std::string json = ", \"inputs\": [";
    for (size_t m = 0; m < paths.size(); ++m) {
        json += std::string(m ? ", " : "") + "{\"input\": " + json_string(paths[m]) +
                ", \"output_vertices\": " + std::to_string(shares[m].vertex_count) +
                ", \"triangles\": " + std::to_string(shares[m].index_count / 3) +
                ", \"charts\": " + std::to_string(per_input[m].charts) +
                ", \"area_3d\": " + json_number(per_input[m].area_3d) +
                ", \"area_texels\": " + json_number(per_input[m].area_texels) + "}";
    }
    const double page_texels = static_cast<double>(stats.atlas_width) * stats.atlas_height;
    json += "], \"pages\": [";
    for (size_t p = 0; p < per_page.size(); ++p) {
        json += std::string(p ? ", " : "") + "{\"page\": " + std::to_string(p) +
                ", \"width\": " + std::to_string(stats.atlas_width) +
                ", \"height\": " + std::to_string(stats.atlas_height) +
                ", \"charts\": " + std::to_string(per_page[p].charts) +
                ", \"utilization\": " + json_number(per_page[p].area_texels / page_texels) + "}";
    }
    json += "], \"charts\": [";
    for (size_t c = 0; c < charts.size(); ++c) {
        const raps_chart& chart = charts[c];
        json +=
            std::string(c ? ", " : "") + "{\"input\": " + std::to_string(chart.mesh) +
            ", \"page\": " + std::to_string(chart.page) + ", \"x\": " + std::to_string(chart.x) +
            ", \"y\": " + std::to_string(chart.y) + ", \"width\": " + std::to_string(chart.width) +
            ", \"height\": " + std::to_string(chart.height) +
            ", \"rotation_deg\": " + json_number(chart.rotation_deg) +
            ", \"triangles\": " + std::to_string(chart.triangle_count) +
            ", \"area_3d\": " + json_number(chart.area_3d) +
            ", \"area_texels\": " + json_number(chart.area_texels) +
            ", \"stretch_l2\": " + json_number(chart.stretch_l2) +
            ", \"scaled_down\": " + ((chart.flags & RAPS_CHART_SCALED_DOWN) ? "true" : "false") +
            ", \"stacked_on\": " + std::to_string(chart.stacked_on) + "}";
    }
    return json + "]";
}

}  // namespace param_report
