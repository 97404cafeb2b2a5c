#pragma once
// CRC-32C (Castagnoli), the checksum of the .oct octree files (internal).
// Parameters from RFC 3720, section 12.1 (iSCSI) and B.4: polynomial 0x1EDC6F41, reflected
// (0x82F63B78 in the LSB-first form used here), initial value and final XOR 0xFFFFFFFF.
// Check value: CRC-32C("123456789") = 0xE3069283.
#include <cstddef>
#include <cstdint>

namespace octrace::io::detail {

/// CRC-32C of `size` bytes, continuing from `crc` (0 to start: the running value without the
/// final XOR is kept inside, so crc32c(b, crc32c(a)) == crc32c(a + b)).
std::uint32_t crc32c(const void* data, std::size_t size, std::uint32_t crc = 0);

}  // namespace octrace::io::detail
