// Text for the HTML report (report_page.hpp): escaping, and files inlined as data URIs so the page
// is one file that opens from file:// with no network.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace rapid {

// &, <, >, " and ' as entities: safe in element text and in quoted attribute values.
std::string html_escape(std::string_view text);

// A value read from summary.json, grid.json or sweep.json as page text: a string escaped, anything
// else its JSON text escaped. Every such value reaches the page through this or html_escape: a
// hand-edited summary may hold a string where the page expects a number (summarize --html-only
// reads the files as they are), and the page must show it, not run it.
std::string html_value(const nlohmann::json& value);

// RFC 4648 base64 with padding, no line breaks.
std::string base64(std::string_view bytes);

// "data:<mime>;base64,…"
std::string data_uri(const std::string& mime, std::string_view bytes);

}  // namespace rapid
