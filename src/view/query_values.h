// The numbers a viewer request carries in its query ("spp=16",
// "origin=0,1,4"), read strictly: the whole text must be the number, and
// a problem comes back as a message for a 400 answer.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "core/vec3.h"

namespace sombra {

// A finite number, or nullopt (then `problem` says why, naming `name`).
std::optional<double> parse_query_number(std::string_view name, std::string_view text, std::string& problem);
// An integer in [least, most], or nullopt with `problem` set.
std::optional<int> parse_query_int(std::string_view name, std::string_view text, int least, int most,
                                   std::string& problem);
// Three finite numbers separated by commas, "x,y,z", or nullopt with `problem` set.
std::optional<Vec3> parse_query_vec3(std::string_view name, std::string_view text, std::string& problem);

}  // namespace sombra
