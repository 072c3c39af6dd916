#!/usr/bin/env bash
# Installs the Debian 12 packages rtiow needs, and only those that are missing. Works as root,
# or as a user with sudo.
#   bash cmake/install-deps.sh            to build, test and benchmark (the README's second command)
#   bash cmake/install-deps.sh --program  to build and run the program alone (the first command):
#                                         no test frameworks, MPI, sanitizer runtime or plotting
set -euo pipefail

# openimageio-tools is the program's too: Debian's OpenImageIO CMake package names its tools'
# files, and find_package(OpenImageIO) fails where they are missing.
packages=(
  build-essential cmake pkg-config
  libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libpng-dev
  libcli11-dev nlohmann-json3-dev rapidjson-dev libeigen3-dev
)
case "${1:-}" in
  --program) ;;
  "")
    packages+=(
      libgtest-dev libgmock-dev libbenchmark-dev
      clang libclang-rt-14-dev
      libopenmpi-dev openmpi-bin
      python3-matplotlib python3-jsonschema
      python3-dev python3-numpy python3-pytest pybind11-dev mypy
    )
    ;;
  *)
    echo "install-deps: unknown argument '$1' (give none, or --program)" >&2
    exit 2
    ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -eq 0 ]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "install-deps: need root or sudo to install: ${missing[*]}" >&2
  exit 1
fi

echo "install-deps: installing ${missing[*]}" >&2
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
  "${missing[@]}" >/dev/null
