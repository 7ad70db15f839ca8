# SPDX-License-Identifier: GPL-3.0-or-later
# Warning and sanitizer flags shared by every auvloop target (through auvloop_options).
add_library(auvloop_options INTERFACE)
target_compile_options(auvloop_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align
  -Woverloaded-virtual -Wconversion -Wsign-conversion -Wdouble-promotion
  -Wformat=2 -Wimplicit-fallthrough)
# GCC 12 at -O2/-O3 reports false positives inside libstdc++ and CGAL templates: -Wrestrict on
# std::string concatenation (GCC bug 105329), -Wmaybe-uninitialized on aggregates holding strings,
# and -Wnull-dereference on std::pair in inlined container code. They are not in our code.
# -Wmissing-field-initializers fires on designated initializers that leave defaulted members out
# ({.dt = 0.01}), which GCC 13 accepts silently (PR c++/96868).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(auvloop_options INTERFACE -Wno-restrict -Wno-maybe-uninitialized
    -Wno-missing-field-initializers)
else()
  target_compile_options(auvloop_options INTERFACE -Wnull-dereference)
endif()
if(AUVLOOP_WERROR)
  target_compile_options(auvloop_options INTERFACE -Werror)
endif()
if(AUVLOOP_FUZZ)
  # Coverage instrumentation for everything; only the fuzz targets link libFuzzer's main.
  target_compile_options(auvloop_options INTERFACE -fsanitize=fuzzer-no-link,address,undefined)
  target_link_options(auvloop_options INTERFACE -fsanitize=address,undefined)
endif()

if(AUVLOOP_SANITIZE)
  target_compile_options(auvloop_options INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(auvloop_options INTERFACE -fsanitize=address,undefined)
endif()

# Embeds a text file as a std::string_view constant so that presets ship inside the binary
# while staying ordinary, documented files in the source tree.
function(auvloop_embed_text target file symbol)
  get_filename_component(_name "${file}" NAME_WE)
  set(_out "${CMAKE_CURRENT_BINARY_DIR}/embedded/${symbol}.cpp")
  add_custom_command(OUTPUT "${_out}"
    COMMAND ${CMAKE_COMMAND} -DIN=${file} -DOUT=${_out} -DSYMBOL=${symbol}
            -P "${PROJECT_SOURCE_DIR}/cmake/EmbedText.cmake"
    DEPENDS "${file}" "${PROJECT_SOURCE_DIR}/cmake/EmbedText.cmake"
    COMMENT "Embedding ${file}")
  target_sources(${target} PRIVATE "${_out}")
endfunction()

# One library per module: auvloop_<name>, aliased auvloop::<name>, public headers in
# <dir>/include/auvloop/<name>/, warnings from auvloop_options.
#   auvloop_module(NAME SOURCES ... [PUBLIC deps...] [PRIVATE deps...])
function(auvloop_module name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "SOURCES;PUBLIC;PRIVATE")
  add_library(auvloop_${name} ${arg_SOURCES})
  add_library(auvloop::${name} ALIAS auvloop_${name})
  target_include_directories(auvloop_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)
  target_link_libraries(auvloop_${name} PUBLIC ${arg_PUBLIC} PRIVATE auvloop_options ${arg_PRIVATE})
endfunction()
