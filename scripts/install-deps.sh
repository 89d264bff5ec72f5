#!/usr/bin/env bash
# Installs the Debian 12 packages ReliefLab needs. Idempotent: when every
# package is already present it only runs dpkg-query and exits in well under a second.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  ninja-build                         # builds: starts a library's files before the libraries it links are linked
  python3                             # figure scripts read rows.csv (scripts/limberger-fig14-figures.sh)
  libembree-dev                       # truth: Embree 3 ray tracing
  libopenimageio-dev openimageio-tools # image files (the tools package is needed by OIIO's CMake config)
  libstb-dev                          # the fallback image module the relocatable package carries
  libopencv-core-dev libopencv-imgproc-dev # PSNR, SSIM, heat-map colour maps
  libglm-dev                          # maths
  libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri # headless GL 4.5 via EGL
  libtomlplusplus-dev                 # sweep configs
  glslang-dev spirv-tools libspirv-cross-c-shared-dev # op counts: GLSL to SPIR-V, counted, and back
  glslang-tools                       # glslang's CMake config names glslangValidator; only suggested by glslang-dev
  libcli11-dev                        # command line
  nlohmann-json3-dev                  # run manifests
  libsqlite3-dev                      # result store (atomic, resumable)
  libassimp-dev                       # meshes (OBJ, PLY) to bake into relief maps and as bases
  libeigen3-dev                       # least squares (per-vertex curvature, chapter 5 Listing 5.8)
  libgtest-dev libgmock-dev libbenchmark-dev
  slurmctld slurmd slurm-client munge # the sharded-sweep test runs a throwaway one-node Slurm
  libjs-d3                            # the HTML report's plots (copied into each report)
  chromium                            # the report's browser test (headless)
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = "installed" ] || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
