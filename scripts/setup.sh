#!/usr/bin/env bash
# Installs everything radflux needs from Debian 12's archive. Idempotent: when every
# package is already present it only checks and returns (well under a second).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libembree-dev libomp-dev libspdlog-dev libfmt-dev libcli11-dev
  libtinyobjloader-dev libtinygltf-dev libstb-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libgrpc++-dev libprotobuf-dev protobuf-compiler protobuf-compiler-grpc
  libsqlite3-dev libzstd-dev libssl-dev openssl python3-yaml
  clang libclang-rt-14-dev gnuplot-nox
  libcpp-httplib-dev libjs-three chromium chromium-driver python3-selenium python3-pil
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "setup: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
