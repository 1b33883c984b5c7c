// FNV-1a, 64 bit: a fast hash of bytes that is the same on every machine and in every release.
// Config hashes, dataset fingerprints, checkpoint checksums and the per-cell bootstrap seeds all
// use this one definition, so files written by one build are read back by the next.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace rapid {

std::uint64_t fnv1a(std::string_view bytes);

// The hash as 16 lower-case hex digits.
std::string fnv1a_hex(std::string_view bytes);

}  // namespace rapid
