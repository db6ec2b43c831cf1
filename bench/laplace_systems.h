// The linear systems the library solves, built as it builds them, for the solver benchmarks
// (raps-bench-solver, raps-bench-ordering): the Laplace system of a disk mesh of the shared data
// with its boundary held, or of the largest chart of the mesh's default atlas (src/atlas/
// atlas_pipeline.h, one thread), cut out of the atlas's output (its seams duplicated, so it is
// the disk the pipeline mapped). Mean value weights with rows scaled to a unit diagonal (the
// disk domain's initial map, as src/planar/laplace_system.cpp; two right-hand sides) or the
// cotangent Laplacian (the atlas's free-boundary map, as src/atlas/free_boundary_map.cpp; one).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/sparse_pattern.h"

namespace raps_bench {

// One linear system as the library builds it: the pattern (structurally symmetric, rows
// sorted, diagonal included), its values, right-hand sides and the unknowns' positions (for
// the own fill-reducing order).
struct System {
    raps::SparsePattern pattern;
    std::vector<double> values;
    std::vector<double> rhs;  // rhs_count columns of pattern.size entries
    int rhs_count = 1;
    std::vector<Eigen::Vector3d> coordinates;
    bool symmetric = false;
    int64_t triangles = 0;
};

// name: "disk:FILE" (meshes/FILE of the data folder, subdivided 1-to-4 `subdivisions` times) or
// "chart:FILE" (its largest atlas chart; `subdivisions` is ignored). Throws std::runtime_error.
System build_system(const std::string& data, const std::string& name, int subdivisions,
                    bool cotangent);

// The Cholesky factor L of the pattern eliminated in `order`: its nonzeros (diagonal included)
// and the flops of the factorization counted as the sum of its squared column counts. From the
// row subtrees of the elimination tree (Liu 1986), O(nnz(L)).
struct FactorSize {
    int64_t nonzeros = 0;
    double flops = 0;
};
FactorSize cholesky_size(const raps::SparsePattern& pattern, const std::vector<int32_t>& order);

// FNV-1a over the bytes of a solution: the benchmarks print it to show which runs gave the
// same bits.
uint64_t bits_hash(const std::vector<double>& x);

}  // namespace raps_bench
