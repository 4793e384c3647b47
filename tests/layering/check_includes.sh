#!/usr/bin/env bash
# The walls between radflux's parts (docs/ARCHITECTURE.md), checked on every #include:
# solver/ includes nothing of the service (no server/, client/, wire/, gRPC or protobuf);
# wire/ nothing of server/ or client/; client/ nothing of server/; server/ nothing of client/;
# solver/mesh/ (patches) nothing of form factors, ray casting or solving.
# Usage: check_includes.sh SOURCE_DIR. Prints every offending line and exits 1 if any.
set -u
cd "$1" || exit 2
status=0
check() {  # check DIR REGEX WHY
  local hits
  hits=$(grep -rnE "^#include [<\"]($2)" "$1" --include='*.h' --include='*.cc' || true)
  if [ -n "$hits" ]; then
    echo "$1 must not include $3:"; echo "$hits"; status=1
  fi
}
check solver 'server/|client/|wire/|grpc|google/protobuf|radflux/v1/' 'the service (server/, client/, wire/, gRPC, protobuf)'
check wire 'server/|client/' 'server/ or client/'
check client 'server/' 'server/ (what both sides need lives in wire/)'
check server 'client/' 'client/'
check solver/mesh 'solver/(formfactor|raytrace|solve|hierarchical|adaptive)/' 'form factors, ray casting or solvers (mesh/ is about patches)'
[ $status -eq 0 ] && echo "layering ok"
exit $status
