#pragma once
// The HTML report's style sheet, inlined in the page's <head>: system fonts
// only (no web fonts), readable contrast, verdicts carried by words and
// symbols as well as colour.
#include <string_view>

namespace vesper::regress {

std::string_view report_css();

}  // namespace vesper::regress
