#include "gltf_primitive_write.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <unordered_map>

#include "gltf_accessors.h"
#include "tangent_frames.h"

namespace raps_gltf {

namespace {

std::vector<float> as_floats(const std::vector<uint8_t>& data, const AccessorLayout& a) {
    const int components = component_count(a.type);
    const uint64_t element = element_size(a.type, a.component_type);
    const size_t n = element ? data.size() / element : 0;
    std::vector<float> out(n * components);
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < components; ++c) {
            out[i * components + c] = static_cast<float>(
                component_value(&data[i * element], a.component_type, a.normalized, c));
        }
    }
    return out;
}

// Output vertices whose weights, summed over every WEIGHTS_n set, are not 1 (the validator's
// ACCESSOR_WEIGHTS_NON_NORMALIZED): counted for the report, never changed.
uint64_t unnormalized_weights(const Asset& asset, const Json& attributes,
                              const std::vector<uint32_t>& vertex_of) {
    std::vector<double> sum(vertex_of.size(), 0.0);
    bool any = false;
    for (auto it = attributes.begin(); it != attributes.end(); ++it) {
        if (it.key().compare(0, 8, "WEIGHTS_") != 0) continue;
        const int accessor = it.value().get<int>();
        const AccessorLayout a = accessor_layout(asset.doc, accessor);
        const std::vector<float> w = as_floats(read_accessor_at(asset, accessor, vertex_of), a);
        const int n = component_count(a.type);
        for (size_t k = 0; k < vertex_of.size(); ++k) {
            for (int c = 0; c < n; ++c) sum[k] += w[k * n + c];
        }
        any = true;
    }
    uint64_t count = 0;
    for (double s : sum) count += any && std::fabs(s - 1.0) > 1e-3;
    return count;
}

// Indices: 16-bit while every index fits below the primitive-restart value 65535.
int write_indices(AccessorWriter& writer, const std::vector<uint32_t>& indices, size_t vertices,
                  int* component_type) {
    const bool wide = vertices > 65535;
    *component_type = wide ? kUnsignedInt : kUnsignedShort;
    std::vector<uint8_t> bytes(indices.size() * (wide ? 4 : 2));
    for (size_t k = 0; k < indices.size(); ++k) {
        if (wide) {
            std::memcpy(&bytes[4 * k], &indices[k], 4);
        } else {
            const uint16_t v = static_cast<uint16_t>(indices[k]);
            std::memcpy(&bytes[2 * k], &v, 2);
        }
    }
    return writer.add(Json::object(), "SCALAR", *component_type, indices.size(), bytes, false,
                      false);
}

// The input's accessors read at a primitive's output vertices, each accessor once.
class GatheredAttributes {
  public:
    GatheredAttributes(const Asset& asset, const std::vector<uint32_t>& vertex_of)
        : asset_(asset), vertex_of_(vertex_of) {}
    const std::vector<uint8_t>& bytes(int accessor) {
        auto it = gathered_.find(accessor);
        if (it == gathered_.end()) {
            const AccessorLayout a = accessor_layout(asset_.doc, accessor);
            it = gathered_.emplace(accessor, read_accessor_at(asset_, accessor, vertex_of_)).first;
        }
        return it->second;
    }
    std::vector<float> floats(int accessor) {
        return as_floats(bytes(accessor), accessor_layout(asset_.doc, accessor));
    }

  private:
    const Asset& asset_;
    const std::vector<uint32_t>& vertex_of_;
    std::map<int, std::vector<uint8_t>> gathered_;
};

// Everything one primitive's accessors are written with.
struct PrimitiveWrite {
    const Asset& asset;
    const BakeOptions& options;
    AccessorWriter& writer;
    const PrimitiveInput& input;
    const PrimitiveShare& share;
    GatheredAttributes gathered;
};

int write_texcoords(PrimitiveWrite& w, const GroupMap& map, PrimitiveReport* pr,
                    double* error_texels) {
    const EncodedTexcoords uv =
        encode_texcoords(w.share.uv, w.options.uv_format, map.page_width, map.page_height);
    *error_texels = std::max(*error_texels, uv.max_error_texels);
    pr->texcoord_component_type = uv.component_type;
    const Json like = uv.normalized ? Json{{"normalized", true}} : Json::object();
    return w.writer.add(like, "VEC2", uv.component_type, w.share.vertex_of.size(), uv.bytes, true,
                        true);
}

int copy_attribute(PrimitiveWrite& w, const std::string& name, int accessor) {
    const Json& like = w.asset.doc["accessors"][static_cast<size_t>(accessor)];
    return w.writer.copy(w.asset, accessor, w.share.vertex_of, w.gathered.bytes(accessor),
                         name == "POSITION" || like.contains("min") || like.contains("max"));
}

// New tangent frames for the new uvs (tangent_frames.h), in an accessor like the old one.
int write_generated_tangents(PrimitiveWrite& w, const Json& old_attributes, int old_tangents) {
    const std::vector<float> frames = tangent_frames(
        w.gathered.floats(old_attributes["POSITION"].get<int>()),
        w.gathered.floats(old_attributes["NORMAL"].get<int>()), w.share.uv, w.share.indices);
    std::vector<uint8_t> bytes(frames.size() * sizeof(float));
    std::memcpy(bytes.data(), frames.data(), bytes.size());
    return w.writer.add(w.asset.doc["accessors"][static_cast<size_t>(old_tangents)], "VEC4", kFloat,
                        w.share.vertex_of.size(), bytes, true, false);
}

// The primitive's attributes, the new set among them; lower sets it lacks get the new uvs too
// (the specification's continuity rule: TEXCOORD_0 .. TEXCOORD_{n-1} must exist), as
// glTF-Transform's unwrap does.
Json write_attributes(PrimitiveWrite& w, int uv_accessor, PrimitiveReport* pr) {
    const std::string set_name = texcoord_name(w.options.texcoord);
    const Json& old_attributes = (*w.input.json)["attributes"];
    Json attributes = Json::object();
    for (auto it = old_attributes.begin(); it != old_attributes.end(); ++it) {
        if (it.key() == set_name) {
            attributes[it.key()] = uv_accessor;
        } else if (it.key() == "TANGENT" && w.input.tangents == TangentPolicy::kDrop) {
            pr->tangents_dropped = true;
        } else if (it.key() == "TANGENT" && w.input.tangents == TangentPolicy::kGenerate) {
            attributes[it.key()] =
                write_generated_tangents(w, old_attributes, it.value().get<int>());
            pr->tangents_generated = true;
        } else {
            attributes[it.key()] = copy_attribute(w, it.key(), it.value().get<int>());
        }
    }
    if (!attributes.contains(set_name)) attributes[set_name] = uv_accessor;
    for (int s = 0; s <= w.options.texcoord; ++s) {
        if (!attributes.contains(texcoord_name(s))) attributes[texcoord_name(s)] = uv_accessor;
        if (attributes[texcoord_name(s)] == uv_accessor) pr->texcoord_sets.push_back(s);
    }
    for (auto it = attributes.begin(); it != attributes.end(); ++it)
        pr->attributes.push_back(it.key());
    return attributes;
}

// Morph targets at the output vertices. Deltas of a rewritten uv set or of replaced tangents
// mean nothing now.
Json write_targets(PrimitiveWrite& w, PrimitiveReport* pr) {
    const std::string set_name = texcoord_name(w.options.texcoord);
    Json targets = Json::array();
    for (const Json& target : (*w.input.json)["targets"]) {
        Json out = Json::object();
        for (auto it = target.begin(); it != target.end(); ++it) {
            if ((it.key() == "TANGENT" && w.input.tangents != TangentPolicy::kKeep) ||
                it.key() == set_name)
                continue;
            out[it.key()] = copy_attribute(w, it.key(), it.value().get<int>());
        }
        targets.push_back(out);
    }
    pr->targets = static_cast<int>(targets.size());
    return targets;
}

void add_to_preview(PrimitiveWrite& w, PreviewGeometry* preview) {
    const std::vector<float> xyz =
        w.gathered.floats((*w.input.json)["attributes"]["POSITION"].get<int>());
    const uint32_t base = static_cast<uint32_t>(preview->positions.size() / 3);
    preview->positions.insert(preview->positions.end(), xyz.begin(), xyz.end());
    preview->uvs.insert(preview->uvs.end(), w.share.uv.begin(), w.share.uv.end());
    for (uint32_t k : w.share.indices) preview->indices.push_back(base + k);
}

}  // namespace

std::string texcoord_name(int set) {
    return "TEXCOORD_" + std::to_string(set);
}

PrimitiveShare share_of(const GroupMap& map, const PrimitiveInput& p, size_t i,
                        PreviewGeometry* preview) {
    PrimitiveShare share;
    std::unordered_map<uint64_t, uint32_t> local;  // (output vertex, input vertex) -> new vertex
    const size_t first = map.first_triangle[i];
    for (size_t t = first; t < map.first_triangle[i + 1]; ++t) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t o = map.indices[3 * t + k];
            const uint32_t v = p.triangles[3 * (t - first) + k];
            const auto added = local.emplace((uint64_t(o) << 32) | v,
                                             static_cast<uint32_t>(share.vertex_of.size()));
            if (added.second) {
                share.vertex_of.push_back(v);
                // raps puts v up; glTF's uv origin is the image's top-left corner.
                share.uv.push_back(static_cast<float>(map.uv[2 * o]));
                share.uv.push_back(static_cast<float>(1.0 - map.uv[2 * o + 1]));
            }
            share.indices.push_back(added.first->second);
        }
        preview->chart_of_triangle.push_back(map.charts[t]);
    }
    return share;
}

// Writes one primitive's new accessors; returns the members its JSON gets (attributes, targets,
// indices, mode).
Json write_primitive(const Asset& asset, const BakeOptions& options, AccessorWriter& writer,
                     const PrimitiveInput& p, const PrimitiveShare& share, const GroupMap& map,
                     PrimitiveReport* pr, GroupReport* report, PreviewGeometry* preview) {
    PrimitiveWrite w{asset, options, writer, p, share, GatheredAttributes(asset, share.vertex_of)};
    Json edit = Json::object();
    edit["attributes"] =
        write_attributes(w, write_texcoords(w, map, pr, &report->uv_error_texels), pr);
    if (p.json->contains("targets")) edit["targets"] = write_targets(w, pr);
    pr->unnormalized_weights =
        unnormalized_weights(asset, (*p.json)["attributes"], share.vertex_of);
    edit["indices"] =
        write_indices(writer, share.indices, share.vertex_of.size(), &pr->index_component_type);
    if (p.json->contains("mode") || p.mode != 4) edit["mode"] = 4;
    add_to_preview(w, preview);
    pr->output_vertices = share.vertex_of.size();
    return edit;
}

}  // namespace raps_gltf
