# Interface targets that carry the project's compile options; every target links them.
add_library(radflux_options INTERFACE)
target_compile_features(radflux_options INTERFACE cxx_std_20)
target_compile_options(radflux_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow
                                                 -Wnon-virtual-dtor -Wconversion-null)
# GCC 12 reports -Wrestrict inside libstdc++'s std::string at -O3 (GCC bug 105329, a
# false positive in code we do not own); it is off for GCC 12 only.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(radflux_options INTERFACE -Wno-restrict)
endif()
if(RADFLUX_WARNINGS_AS_ERRORS)
  target_compile_options(radflux_options INTERFACE -Werror)
endif()
if(RADFLUX_SANITIZE)
  target_compile_options(radflux_options INTERFACE -fsanitize=address,undefined
                                                   -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(radflux_options INTERFACE -fsanitize=address,undefined)
endif()
if(RADFLUX_FUZZ)
  target_compile_options(radflux_options INTERFACE -fsanitize=fuzzer-no-link,address,undefined)
  target_link_options(radflux_options INTERFACE -fsanitize=address,undefined)
endif()
