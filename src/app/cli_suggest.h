// Clearer words than the option parser's for the mistakes a new user makes
// first (issue 39): a misspelt option, a scene given without a command.
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace sombra {

// The edit distance between two words (insertions, deletions,
// substitutions and swaps of neighbours, each 1).
int edit_distance(const std::string& a, const std::string& b);

// What went wrong with argv, said better than the parser's own message,
// when it is one of those mistakes: "unknown option '--widht' (did you mean
// --width?)", "'cornell.json' is not a command: ...". Nothing otherwise.
std::optional<std::string> parse_error_hint(const CLI::App& app, int argc, const char* const* argv);

}  // namespace sombra
