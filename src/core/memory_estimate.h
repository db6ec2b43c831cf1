// The peak memory a run is estimated to add, which RAPS_PARAM_MAX_MEMORY_MB is checked against
// before any work is done. The model and the measurements behind its numbers are in
// memory_estimate.cpp.
#pragma once

#include "core/settings.h"
#include "core/triangle_mesh.h"

namespace raps {

// Bytes; a double, so that no triangle count overflows it.
double estimated_peak_bytes(const TriangleMesh& mesh, const Settings& settings);

}  // namespace raps
