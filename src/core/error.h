// Errors inside the library. Algorithms throw raps::Error with a code and a message naming the
// problem; the C API (src/c_api.cpp) is the only place that catches and turns them into a status.
// The codes have the numeric values of the public status codes (checked there by static_assert),
// but nothing here depends on the public header.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace raps {

enum class ErrorCode : int32_t {
    kInvalidArgument = 1,
    kOutOfMemory = 2,
    kEmptyMesh = 3,
    kIndexCount = 4,
    kIndexOutOfRange = 5,
    kNonFinitePosition = 6,
    kRepeatedVertex = 7,
    kZeroAreaTriangle = 8,
    kNonManifoldEdge = 9,
    kNonManifoldVertex = 10,
    kInconsistentOrientation = 11,
    kIsolatedVertex = 12,
    kMultipleComponents = 13,
    kNoBoundary = 14,
    kMultipleBoundaries = 15,
    kNonzeroGenus = 16,
    kTooLarge = 17,
    kCancelled = 18,
    kSolverFailed = 19,
    kInvalidOperation = 20,
    kInternal = 21,
    kOpenMesh = 22,
    kInvalidTransform = 23,
    kGroupCount = 24,
    kSeamNotAnEdge = 25,
    kUvCount = 26,
    kNonFiniteUv = 27,
    kDegenerateUvChart = 28,
};

class Error : public std::runtime_error {
  public:
    Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    ErrorCode code() const { return code_; }

  private:
    ErrorCode code_;
};

}  // namespace raps
