#pragma once
// Private to core: min/max of valid samples over index boxes, for pruning the octree build.
#include "octrace/build/ScalarField.h"

#include <cstdint>
#include <vector>

namespace octrace::detail {

/// Level l (l >= 1) stores, for each block of 2^l x 2^l x 2^l samples, the minimum and maximum
/// of its valid samples (min = +inf when none) and whether it holds a masked one. Level 0 is
/// the field itself (NaN = masked).
class MinMaxPyramid {
public:
    /// `samples`: the field's values with NaN at masked samples (not owned; must outlive this).
    MinMaxPyramid(const float* samples, ivec3 dims);
    /// Min and max over the valid samples of the inclusive index box [lo, hi] (conservative:
    /// may cover a few more samples). Returns min > max when no sample is valid. `masked`, when
    /// given, is set when some sample of the box (or of the few more) is masked.
    void query(ivec3 lo, ivec3 hi, float& mn, float& mx, bool* masked = nullptr) const;
    /// Bytes the pyramid of a field of these dims allocates (for memory estimates).
    static std::uint64_t bytesFor(ivec3 dims);

private:
    struct Level {
        ivec3 dims;
        std::vector<float> mn, mx;
        std::vector<std::uint8_t> masked;
    };
    const float* samples_;
    ivec3 dims_;
    std::vector<Level> levels_;  // levels_[0] is level 1
};

}  // namespace octrace::detail
