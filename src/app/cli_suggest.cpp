#include "app/cli_suggest.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <string_view>
#include <vector>

namespace sombra {

int edit_distance(const std::string& a, const std::string& b) {
    // Damerau–Levenshtein (optimal string alignment): a swap of two letters is one slip.
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1));
    for (std::size_t i = 0; i <= n; ++i) d[i][0] = static_cast<int>(i);
    for (std::size_t j = 0; j <= m; ++j) d[0][j] = static_cast<int>(j);
    for (std::size_t i = 1; i <= n; ++i)
        for (std::size_t j = 1; j <= m; ++j) {
            const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[n][m];
}

namespace {

// The closest of `names` to `word`, when it is close enough to be a slip.
std::optional<std::string> nearest(const std::string& word, const std::vector<std::string>& names) {
    std::optional<std::string> best;
    int best_distance = std::max(2, static_cast<int>(word.size()) / 4) + 1;
    for (const std::string& name : names) {
        const int d = edit_distance(word, name);
        if (d < best_distance) {
            best_distance = d;
            best = name;
        }
    }
    return best;
}

std::vector<std::string> command_names(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
        names.push_back(sub->get_name());
    return names;
}

std::string listed(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
    return text;
}

}  // namespace

std::optional<std::string> parse_error_hint(const CLI::App& app, int argc, const char* const* argv) {
    if (argc < 2) return std::nullopt;
    const std::string first = argv[1];
    const std::vector<std::string> commands = command_names(app);
    if (first.empty() || first[0] == '-') return std::nullopt;
    if (std::find(commands.begin(), commands.end(), first) == commands.end()) {
        if (const std::optional<std::string> close = nearest(first, commands))
            return "unknown command '" + first + "' (did you mean " + *close + "?)";
        if (first.find('.') != std::string::npos)
            return "'" + first + "' is not a command: to render it, run 'sombra render " + first +
                   "' (commands: " + listed(commands) + ")";
        return "unknown command '" + first + "' (commands: " + listed(commands) + ")";
    }
    // A misspelt long option of the command given.
    const CLI::App* command = app.get_subcommand(first);
    std::vector<std::string> options{"--help"};
    for (const CLI::Option* option : command->get_options())
        for (const std::string& name : option->get_lnames()) options.push_back("--" + name);
    for (int i = 2; i < argc; ++i) {
        std::string word = argv[i];
        if (word.rfind("--", 0) != 0 || word == "--") continue;
        word = word.substr(0, word.find('='));
        if (std::find(options.begin(), options.end(), word) != options.end()) continue;
        if (const std::optional<std::string> close = nearest(word, options))
            return "unknown option '" + word + "' (did you mean " + *close + "?)";
        return "unknown option '" + word + "'";
    }
    return std::nullopt;
}

}  // namespace sombra
