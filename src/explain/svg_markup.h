// The SVG markup explain's pictures share: coordinates as text and text
// made safe for an attribute or an element.
#pragma once

#include <string>

namespace sombra {

// A coordinate or length with one decimal ("12.5"): a tenth of a pixel is
// finer than any screen shows, and the picture stays small.
std::string svg_number(float v);

// `text` with <, >, & and " written as entities.
std::string escape_xml(const std::string& text);

}  // namespace sombra
