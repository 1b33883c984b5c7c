// User text inside a one-line message: a grid's name, a key or a path may hold any byte, and a
// control character would cut the message (NUL ends what() early) or break it over lines.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rapid {

// `text` with every control byte (below 0x20, and 0x7f) written as \xNN; other bytes unchanged.
std::string printable(std::string_view text);

// "a, b, c": the names a message lists as the accepted choices.
std::string comma_joined(const std::vector<std::string>& names);

}  // namespace rapid
