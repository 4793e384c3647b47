// Where the tests find the repository's files. The checkout's path is compiled into one small
// library (source_path.cc) and nowhere else, so every other test source compiles to the same
// bytes in every checkout and the compiler cache serves them all.
#pragma once

#include <string>
#include <string_view>

namespace radflux::testing {

// The repository root joined with `relative` ("scenes/cornell_box.obj", "../shared/scenes/").
std::string SourcePath(std::string_view relative);

}  // namespace radflux::testing
