# RADFLUX_STATIC_GRPC: links abseil, protobuf and gRPC, and the C libraries gRPC needs
# (OpenSSL, c-ares, zlib), from their static archives (Debian ships them beside the shared
# ones) instead of ~65 shared objects. A client process start (`radflux-service list`) then
# takes 5 ms of CPU instead of 13: most of the difference was the dynamic loader resolving
# gRPC's and abseil's symbols in each other (bench/RESULTS.md, "Service overhead (issue 4)");
# libcrypto alone has 21,000 relocations, ~2 ms of every `radflux-service` start. Every
# target of the build switches together, and only when every one of these libraries has its
# archive, so no process ever holds two copies of abseil or OpenSSL. re2 stays shared: gRPC
# finds it through pkg-config, as an interface target with no location of its own.
option(RADFLUX_STATIC_GRPC "Link abseil, protobuf, gRPC, OpenSSL, c-ares and zlib statically" ON)

# Points every imported (non-interface) target of this directory whose library is one of
# those above at the static archive of the same name, if all of them have one (else changes
# nothing and says why).
function(radflux_use_static_grpc_archives)
  get_directory_property(targets IMPORTED_TARGETS)
  set(changes "")
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "INTERFACE_LIBRARY" OR type STREQUAL "EXECUTABLE")
      continue()
    endif()
    foreach(property IMPORTED_LOCATION IMPORTED_LOCATION_NONE IMPORTED_LOCATION_RELEASE)
      get_target_property(location ${target} ${property})
      if(NOT location MATCHES "/lib((absl|grpc|gpr|upb|address_sorting|protobuf)[a-z0-9_+-]*|ssl|crypto|cares|z)\\.so")
        continue()
      endif()
      get_filename_component(dir "${location}" DIRECTORY)
      set(archive "${dir}/lib${CMAKE_MATCH_1}.a")
      if(NOT EXISTS "${archive}")
        message(STATUS "RADFLUX_STATIC_GRPC: no ${archive}; linking the shared objects")
        return()
      endif()
      list(APPEND changes "${target}|${property}|${archive}")
    endforeach()
  endforeach()
  foreach(change IN LISTS changes)
    string(REPLACE "|" ";" parts "${change}")
    list(GET parts 0 target)
    list(GET parts 1 property)
    list(GET parts 2 archive)
    set_target_properties(${target} PROPERTIES ${property} "${archive}")
  endforeach()
endfunction()

if(RADFLUX_STATIC_GRPC)
  radflux_use_static_grpc_archives()
endif()
