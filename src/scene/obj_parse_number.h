// The numbers of an OBJ line, read the way tinyobjloader decides what a
// number is (so that sombra keeps its outcome on malformed files), with the
// value rounded correctly (std::from_chars, the same float strtof gives).
#pragma once

namespace sombra {

// Reads the longest prefix of [first, last) that tinyobjloader's
// tryParseDouble accepts: [sign] (digits | '.') [. digits] [e|E [sign] digits]
// ("3.1+e2" reads as 3.1, "1.#IND" as 1, "-." as -0). Returns the end of that
// prefix with `value` set to strtof's float for it (±inf beyond the float
// range), or nullptr where tinyobjloader fails ("nan", "1e", an exponent of
// more than 9 digits), leaving `value` unchanged.
const char* read_obj_real(const char* first, const char* last, float& value);

// C's atoi on [first, last) as glibc computes it: leading white space, a
// sign, digits; strtol saturates at 64 bits and the result is cut to int.
// tinyobjloader reads every face index this way.
int obj_atoi(const char* first, const char* last);

}  // namespace sombra
