// User text inside a one-line message: a grid's name, a key or a path may hold any byte, and a
// control character would cut the message (NUL ends what() early) or break it over lines.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rapid {

// `text` with every control byte (below 0x20, and 0x7f) written as \xNN; other bytes unchanged.
std::string printable(std::string_view text);

// printable(text) cut to about `max_bytes` (at a character boundary) with how much was left out:
// an error line that reaches a record, a report or a terminal (an external method may print a
// 20 MB line; issue #67).
std::string excerpt(std::string_view text, std::size_t max_bytes = 500);

// A name that may name a folder and appear in every report format (LaTeX, markdown, CSV, HTML)
// as it is: non-empty, not "." or "..", only letters, digits, '.', '_' and '-' (a grid's name, a
// scenario's name).
bool is_safe_name(std::string_view name);

// Display text for the reports: non-empty, only letters, digits, spaces and - _ . , ( ) + / : '
// (a scenario's display name). None of LaTeX's, markdown's, CSV's or HTML's special characters
// (\ { } ^ ~ $ & % # | < > " ` = @ and line breaks) can reach a table through it (issue 46).
bool is_plain_text(std::string_view text);

// "a, b, c": the names a message lists as the accepted choices.
std::string comma_joined(const std::vector<std::string>& names);

}  // namespace rapid
