// printable(): user text inside a one-line message keeps every byte visible.
#include <gtest/gtest.h>

#include <string>

#include "core/printable.hpp"

using rapid::printable;

TEST(Printable, ControlBytesAreEscapedAndTheRestKept) {
  EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(printable("line\nnext\ttab\r\x7f"), "line\\x0anext\\x09tab\\x0d\\x7f");
  EXPECT_EQ(printable("plain text, 'quoted' — UTF-8 ε"), "plain text, 'quoted' — UTF-8 ε");
  EXPECT_EQ(printable(""), "");
}
