# SPDX-License-Identifier: GPL-3.0-or-later
# Script mode: writes OUT, a C++ source defining `std::string_view SYMBOL` with the bytes of IN.
file(READ "${IN}" _hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "'\\\\x\\1'," _chars "${_hex}")
file(WRITE "${OUT}.tmp"
  "// Generated from ${IN}; do not edit.\n#include <string_view>\n"
  "namespace auvloop::embedded {\nstatic constexpr char data[] = {${_chars} '\\0'};\n"
  "extern const std::string_view ${SYMBOL};\n"
  "const std::string_view ${SYMBOL}{data, sizeof(data) - 1};\n}\n")
file(RENAME "${OUT}.tmp" "${OUT}")
