// Reading the shared real meshes for the C tests, through the samples' OBJ/OFF reader.
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "mesh_io.h"
#include "test_meshes.h"

extern "C" {

const char* shared_data_dir(void) {
    return RAPS_SHARED_DATA_DIR;
}

// Returns 0 and fills *out, or writes the reason into `error` and returns -1.
int read_shared_mesh(const char* name, test_mesh* out, char* error, size_t error_size) {
    try {
        const std::string path = std::string(RAPS_SHARED_DATA_DIR) + "/meshes/" + name;
        const raps_samples::PolygonMesh mesh = raps_samples::read_mesh(path);
        const std::vector<uint32_t> triangles = mesh.triangles();
        out->vertex_count = mesh.vertex_count();
        out->index_count = triangles.size();
        out->positions =
            static_cast<double*>(std::malloc(mesh.positions.size() * sizeof(double) + 1));
        out->indices = static_cast<uint32_t*>(std::malloc(triangles.size() * sizeof(uint32_t) + 1));
        if (!out->positions || !out->indices) throw std::runtime_error("out of memory");
        std::memcpy(out->positions, mesh.positions.data(), mesh.positions.size() * sizeof(double));
        std::memcpy(out->indices, triangles.data(), triangles.size() * sizeof(uint32_t));
        return 0;
    } catch (const std::exception& e) {
        std::snprintf(error, error_size, "%s", e.what());
        return -1;
    }
}

}  // extern "C"
