# Turns the viewer's page (src/view/page.html) into a C++ header holding it
# as one raw string literal, so that the binary serves it from memory:
#
#   cmake -DIN=page.html -DOUT=view/view_page.h -P embed_page.cmake
cmake_minimum_required(VERSION 3.25)
file(READ "${IN}" page)
string(FIND "${page}" ")sombra_page\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} contains the raw string's end marker )sombra_page\"")
endif()
file(WRITE "${OUT}.tmp" "// Generated from src/view/page.html by src/view/embed_page.cmake: do not edit.
#pragma once

#include <string_view>

namespace sombra {

// The viewer's page: one HTML file with its script and style inline.
inline constexpr std::string_view kViewPage = R\"sombra_page(${page})sombra_page\";

}  // namespace sombra
")
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUT}.tmp")
