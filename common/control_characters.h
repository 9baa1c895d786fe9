#pragma once
// Names people give (jobs, workers, assets) end up on terminals and in file
// names: a control character in one could move the cursor, recolour or
// rewrite what `vesper status` shows, or split a log line. They are refused
// where a name enters the farm and escaped where one is printed.
#include <string>
#include <string_view>

namespace vesper {

// "contains a control character (U+001B)" for the first C0 control, DEL or
// C1 control (U+0080..U+009F, which some terminals obey too) in `s`; "" when
// there is none.
std::string control_character_problem(std::string_view s);

// `s` safe to print on a terminal: control characters as \n, \r, \t or
// \xNN / \u00NN, a backslash doubled, bytes that are not UTF-8 as \xNN.
std::string escape_control_characters(std::string_view s);

}  // namespace vesper
