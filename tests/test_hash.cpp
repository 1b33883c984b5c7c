// FNV-1a against the published 64-bit test vectors: config hashes, dataset fingerprints and
// checkpoint checksums written by earlier builds must keep reading back.
#include <gtest/gtest.h>

#include "core/hash.hpp"

using namespace rapid;

TEST(Fnv1a, MatchesThePublishedTestVectors) {
  EXPECT_EQ(fnv1a(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a("foobar"), 0x85944171f73967e8ULL);
  EXPECT_EQ(fnv1a_hex("a"), "af63dc4c8601ec8c");
}
