#include "report.h"

#include <cmath>

#include "parameter_text.h"

namespace raps_gltf {

namespace {

const char* choice(raps_param param, int64_t value) {
    switch (param) {
        case RAPS_PARAM_WEIGHTS: {
            static const char* names[] = {"mvc", "cotan", "uniform"};
            return value >= 0 && value < 3 ? names[value] : "?";
        }
        case RAPS_PARAM_MONITOR: {
            static const char* names[] = {"none", "area", "length", "angle"};
            return value >= 0 && value < 4 ? names[value] : "?";
        }
        case RAPS_PARAM_ITERATION_MODE:
            return value == RAPS_ITERATION_REAPPLY ? "reapply" : "accumulate";
        case RAPS_PARAM_ATLAS_ROTATION: {
            static const char* names[] = {"any", "quarter", "none"};
            return value >= 0 && value < 3 ? names[value] : "?";
        }
        default:
            return "?";
    }
}

Json chart_json(const raps_chart& c, const SceneReport& scene) {
    Json j = Json::object();
    j["mesh"] = scene.packed_meshes.at(c.mesh);
    j["page"] = c.page;
    j["rect"] = {c.x, c.y, c.width, c.height};
    j["rotation_deg"] = json_number(c.rotation_deg);
    j["triangles"] = c.triangle_count;
    j["area_3d"] = json_number(c.area_3d);
    j["area_texels"] = json_number(c.area_texels);
    j["stretch_l2"] = json_number(c.stretch_l2);
    j["scaled_down"] = (c.flags & RAPS_CHART_SCALED_DOWN) != 0;
    if (c.flags & RAPS_CHART_STACKED) j["stacked_on"] = c.stacked_on;
    return j;
}

// Per page: its size (every page has the atlas's) and the share of its texels charts cover.
Json pages_json(const SceneReport& scene) {
    const raps_stats& s = scene.stats;
    std::vector<double> covered(s.page_count, 0.0);
    std::vector<uint64_t> charts(s.page_count, 0);
    for (const raps_chart& c : scene.charts) {
        if (c.page >= covered.size()) continue;
        // A stacked chart's texels are its original's: a page counts them once.
        if (!(c.flags & RAPS_CHART_STACKED)) covered[c.page] += c.area_texels;
        ++charts[c.page];
    }
    Json pages = Json::array();
    const double texels = double(s.atlas_width) * double(s.atlas_height);
    for (size_t p = 0; p < covered.size(); ++p) {
        pages.push_back({{"page", p},
                         {"size", {s.atlas_width, s.atlas_height}},
                         {"charts", charts[p]},
                         {"utilization", json_number(texels > 0 ? covered[p] / texels : 0.0)}});
    }
    return pages;
}

Json scene_json(const SceneReport& scene) {
    Json out = Json::object();
    out["scene"] = scene.scene;
    out["texels_per_unit"] = json_number(scene.stats.texels_per_unit);
    out["atlas"] = {scene.stats.atlas_width, scene.stats.atlas_height};
    out["page_count"] = scene.stats.page_count;
    out["charts"] = scene.stats.chart_count;
    out["scaled_down_charts"] = scene.stats.scaled_down_charts;
    out["utilization"] = json_number(scene.stats.utilization);
    Json times = Json::object();
    for (int p = 0; p < RAPS_PHASE_COUNT; ++p)
        times[raps_samples::phase_name(static_cast<raps_phase>(p))] =
            json_number(scene.phase_ms[p]);
    times["total"] = json_number(scene.total_ms);
    out["time_ms"] = times;
    Json meshes = Json::array();
    for (const SceneMeshReport& m : scene.meshes) {
        Json j = {{"mesh", m.mesh},
                  {"instances", m.instances},
                  {"scale", json_number(m.scale)},
                  {"scales", m.scales},
                  {"several_scales", m.scales.size() > 1},
                  {"skinned", m.skinned}};
        if (m.shares_atlas_of >= 0) j["shares_atlas_of"] = m.shares_atlas_of;
        meshes.push_back(j);
    }
    out["meshes"] = meshes;
    out["pages"] = pages_json(scene);
    Json charts = Json::array();
    for (const raps_chart& c : scene.charts) charts.push_back(chart_json(c, scene));
    out["chart_list"] = charts;
    return out;
}

}  // namespace

Json json_number(double value) {
    return std::isfinite(value) ? Json(value) : Json(nullptr);
}

Json settings_json(const raps_settings* settings, const BakeOptions& options) {
    Json out = Json::object();
    out["texcoord"] = options.texcoord;
    out["overwrite"] = options.overwrite;
    out["group"] = options.grouping == Grouping::kMesh        ? "mesh"
                   : options.grouping == Grouping::kPrimitive ? "primitive"
                                                              : "scene";
    out["keep_uv_seams"] = options.keep_uv_seams;
    out["uv_format"] = options.uv_format == UvFormat::kFloat32 ? "float" : "unorm16";
    const raps_param choices[] = {RAPS_PARAM_WEIGHTS, RAPS_PARAM_MONITOR, RAPS_PARAM_ITERATION_MODE,
                                  RAPS_PARAM_ATLAS_ROTATION};
    const raps_param numbers[] = {RAPS_PARAM_ALPHA,
                                  RAPS_PARAM_ITERATIONS,
                                  RAPS_PARAM_ATLAS_RESOLUTION,
                                  RAPS_PARAM_ATLAS_PADDING,
                                  RAPS_PARAM_WELD_TOLERANCE,
                                  RAPS_PARAM_HARD_EDGE_ANGLE,
                                  RAPS_PARAM_ATLAS_MAX_L2_STRETCH,
                                  RAPS_PARAM_ATLAS_MAX_LINF_STRETCH,
                                  RAPS_PARAM_MAX_TRIANGLES,
                                  RAPS_PARAM_THREADS,
                                  RAPS_PARAM_ATLAS_TEXELS_PER_UNIT,
                                  RAPS_PARAM_ATLAS_MAX_WIDTH,
                                  RAPS_PARAM_ATLAS_MAX_HEIGHT,
                                  RAPS_PARAM_ATLAS_MARGIN,
                                  RAPS_PARAM_ATLAS_BLOCK_ALIGN,
                                  RAPS_PARAM_ATLAS_WHOLE_TEXELS,
                                  RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS,
                                  RAPS_PARAM_ATLAS_STACK,
                                  RAPS_PARAM_ATLAS_STACK_TOLERANCE};
    for (raps_param p : choices) {
        const char* name = nullptr;
        raps_param_info(p, &name, nullptr, nullptr, nullptr, nullptr);
        int64_t value = 0;
        raps_settings_get_int(settings, p, &value);
        out[name] = choice(p, value);
    }
    for (raps_param p : numbers) {
        const char* name = nullptr;
        int32_t is_float = 0;
        raps_param_info(p, &name, &is_float, nullptr, nullptr, nullptr);
        if (is_float) {
            double value = 0;
            raps_settings_get_float(settings, p, &value);
            out[name] = json_number(value);
        } else {
            int64_t value = 0;
            raps_settings_get_int(settings, p, &value);
            out[name] = value;
        }
    }
    return out;
}

Json bake_json(const BakeResult& bake) {
    Json groups = Json::array();
    for (const GroupReport& g : bake.groups) {
        Json j = Json::object();
        j["mesh"] = g.mesh;
        j["name"] = g.mesh_name;
        j["primitives"] = g.primitives;
        j["triangles"] = g.triangles;
        j["input_vertices"] = g.input_vertices;
        j["output_vertices"] = g.output_vertices;
        j["charts"] = g.stats.chart_count;
        j["atlas"] = {g.stats.atlas_width, g.stats.atlas_height};
        j["utilization"] = json_number(g.stats.utilization);
        j["page"] = g.page;
        if (g.uv_error_texels > 0) j["unorm16_max_move_texels"] = json_number(g.uv_error_texels);
        j["distortion"] = {{"area_log_mean", json_number(g.stats.area_log_mean)},
                           {"area_max", json_number(g.stats.area_max)},
                           {"angle_mean_deg", json_number(g.stats.angle_mean_deg)},
                           {"angle_max_deg", json_number(g.stats.angle_max_deg)},
                           {"stretch_l2", json_number(g.stats.stretch_l2)},
                           {"stretch_linf", json_number(g.stats.stretch_linf)},
                           {"flipped_triangles", g.stats.flipped_triangles},
                           {"zero_area_triangles", g.stats.zero_area_triangles}};
        if (g.reused_from_mesh >= 0) {
            j["reused_from_mesh"] = g.reused_from_mesh;
        } else {
            Json times = Json::object();
            for (int p = 0; p < RAPS_PHASE_COUNT; ++p)
                times[raps_samples::phase_name(p)] = json_number(g.phase_ms[p]);
            times["total"] = json_number(g.total_ms);
            j["time_ms"] = times;
        }
        groups.push_back(j);
    }
    Json primitives = Json::array();
    for (const PrimitiveReport& p : bake.primitives) {
        static const char* modes[] = {"points",    "lines",          "line_loop",   "line_strip",
                                      "triangles", "triangle_strip", "triangle_fan"};
        Json j = Json::object();
        j["mesh"] = p.mesh;
        j["primitive"] = p.primitive;
        j["input_mode"] = modes[p.input_mode];
        j["triangles"] = p.triangles;
        j["input_vertices"] = p.input_vertices;
        j["output_vertices"] = p.output_vertices;
        j["indices"] = p.index_component_type == 5125 ? "uint32" : "uint16";
        j["uv_format"] = p.texcoord_component_type == 5123 ? "unorm16" : "float";
        j["attributes"] = p.attributes;
        j["texcoord_sets"] = p.texcoord_sets;
        j["morph_targets"] = p.targets;
        j["tangents"] = p.tangents_dropped     ? "dropped"
                        : p.tangents_generated ? "generated"
                                               : "kept";
        j["unnormalized_weights"] = p.unnormalized_weights;
        primitives.push_back(j);
    }
    Json skipped = Json::array();
    for (const SkipReport& s : bake.skipped) {
        skipped.push_back({{"mesh", s.mesh}, {"primitive", s.primitive}, {"reason", s.reason}});
    }
    Json out = Json::object();
    out["baked"] = {{"groups", bake.groups.size()},
                    {"primitives", bake.primitives.size()},
                    {"triangles", bake.baked_triangles}};
    out["groups"] = groups;
    if (bake.scene.enabled) out["scene"] = scene_json(bake.scene);
    out["primitives"] = primitives;
    out["skipped"] = skipped;
    out["notes"] = bake.notes;
    return out;
}

Json output_json(const WriteReport& write) {
    Json out = Json::object();
    out["files"] = write.files;
    out["bytes"] = write.bytes;
    out["unused_data_removed"] = write.pruned;
    if (write.pruned) {
        out["removed_accessors"] = write.removed_accessors;
        out["removed_buffer_views"] = write.removed_buffer_views;
    } else {
        out["kept_unused_data_because"] = write.kept_unused_because;
    }
    out["repaired_buffer_views"] = write.repaired_buffer_views;
    out["embedded_images"] = write.embedded_images;
    out["copied_images"] = write.copied_images;
    return out;
}

}  // namespace raps_gltf
