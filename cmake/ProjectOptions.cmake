# Interface targets that carry the project's compile options; every target links them.
add_library(radflux_options INTERFACE)
target_compile_features(radflux_options INTERFACE cxx_std_20)
target_compile_options(radflux_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow
                                                 -Wnon-virtual-dtor -Wconversion-null)
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
