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
// A figure with at most `digits` significant digits, no trailing zeros, no
// exponent for ordinary magnitudes ("0.0123", "4.56", "1.2", "1235"); NaN or
// infinite as "n/a".
std::string format_figure(double value, int digits = 3);

// `value` with `decimals` decimals, trailing zeros and a bare point dropped,
// never "-0" ("1.20" -> "1.2", "3.00" -> "3").
std::string trimmed_fixed(double value, int decimals);

// "[A-Za-z0-9_.-]" kept, anything else '_': a file name from a scene or
// layer name (never empty, never "." or "..").
std::string safe_file_name(std::string_view name);

}  // namespace vesper::regress
