// The preview PNG: on the left the uv layout of every atlas (charts filled, chart outlines
// drawn), on the right the asset's default scene rendered with a checker texture looked up
// through the new uvs, so that stretched or squeezed squares show the distortion at a glance.
// A small software rasterizer (orthographic three-quarter view, z-buffer, two-sided Lambert
// shading, 2x2 supersampling); skins and morph targets are drawn in their rest pose.
#pragma once

#include <string>

#include "gltf_bake.h"
#include "gltf_load.h"

namespace raps_gltf {

struct PreviewOptions {
    int height = 512;  // of each square panel; the image is 2 * height wide
    int checks = 32;   // checker squares along each uv axis
};

// Writes the PNG atomically. Throws GltfError("io", ...) on failure.
void write_preview(const std::string& path, const Asset& asset, const BakeResult& bake,
                   const PreviewOptions& options);

}  // namespace raps_gltf
