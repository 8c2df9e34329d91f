// How sombra reports what went wrong with an input: every user-facing failure
// is one line "sombra: error: WHERE: WHAT"; warnings are collected, not printed,
// so that library code never writes to the terminal itself.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace sombra {

// A wrong input. `where` names the file and the place in it (file:line,
// file:line:col, a JSON path, or a command-line option); `what` says what is wrong.
class Error : public std::runtime_error {
public:
    Error(std::string where, std::string what)
        : std::runtime_error(where + ": " + what), where_(std::move(where)), what_(std::move(what)) {}
    const std::string& where() const { return where_; }
    const std::string& message() const { return what_; }

private:
    std::string where_;
    std::string what_;
};

// A wrong option that shows only once the scene is read (--denoise on a
// scene of 1 sample per pixel): on the command line it is a command-line
// error, exit status 2, like one the parser catches.
class UsageError : public Error {
public:
    using Error::Error;
};

// `text` kept to one line whatever the paths in it hold: control characters
// (a newline or NUL in a file name) are shown as '?'.
inline std::string one_line_message(std::string text) {
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return text;
}

// Non-fatal findings (a missing MTL file, clamped colours, dropped faces),
// gathered while loading and printed by the app as "sombra: warning: WHERE: WHAT".
struct Diagnostics {
    std::vector<std::string> warnings;
    void warn(const std::string& where, const std::string& what) { warnings.push_back(where + ": " + what); }
};

}  // namespace sombra
