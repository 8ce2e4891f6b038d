// The one FNV-1a hash (Util/Fnv1a.h) against the published 64-bit FNV-1a test vectors.
#include "Util/Fnv1a.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace fiberpli;

TEST(Fnv1a, PublishedVectors)
{
  EXPECT_EQ(fnv1a("", 0), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a("a", 1), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a("foobar", 6), 0x85944171f73967e8ULL);
}

TEST(Fnv1a, PiecewiseEqualsWhole)
{
  const char* text = "FiberPLI solver checkpoint";
  std::uint64_t h = kFnv1aOffset;
  fnv1aAdd(h, text, 8);
  fnv1aAdd(h, text + 8, std::strlen(text) - 8);
  EXPECT_EQ(h, fnv1a(text, std::strlen(text)));
  EXPECT_NE(fnv1a(text, 5, 1), fnv1a(text, 5)); // the start value matters
}
