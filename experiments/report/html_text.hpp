// Text for the HTML report (report_page.hpp): escaping, and files inlined as data URIs so the page
// is one file that opens from file:// with no network.
#pragma once

#include <string>
#include <string_view>

namespace rapid {

// &, <, >, " and ' as entities: safe in element text and in quoted attribute values.
std::string html_escape(std::string_view text);

// RFC 4648 base64 with padding, no line breaks.
std::string base64(std::string_view bytes);

// "data:<mime>;base64,…"
std::string data_uri(const std::string& mime, std::string_view bytes);

}  // namespace rapid
