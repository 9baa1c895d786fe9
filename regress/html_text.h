#pragma once
// Text as the HTML report writes it: escaped for element content and
// attribute values, and numbers in the few forms the report shows.
#include <string>
#include <string_view>

namespace vesper::regress {

// &, <, >, " and ' as character references: safe in text and in quoted attributes.
std::string html_escape(std::string_view text);

// A relative change as a signed or plain percentage with 2 significant
// digits at least ("+4.1 %", "0.52 %"); NaN or infinite as "n/a".
std::string format_percent(double relative, bool sign = false);
// Seconds: "0.84 s", "12.3 s", "4 min 05 s"; NaN or negative as "n/a".
std::string format_seconds(double seconds);
// A figure with `digits` significant digits, no exponent for ordinary
// magnitudes ("0.0123", "4.56", "1230"); NaN or infinite as "n/a".
std::string format_figure(double value, int digits = 3);

// "[A-Za-z0-9_.-]" kept, anything else '_': a file name from a scene or
// layer name (never empty, never "." or "..").
std::string safe_file_name(std::string_view name);

}  // namespace vesper::regress
