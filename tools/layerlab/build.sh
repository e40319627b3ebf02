#!/bin/sh
# Builds layerlab's Python module from its public source against Debian 12's packages (CMakeLists.txt here).
# usage: tools/layerlab/build.sh LAYERLAB_MIRROR FILESYSTEM_MIRROR TINYFORMAT_MIRROR [BUILD_DIR]
#   the three arguments are bare git directories of github.com/wjakob/{layerlab,filesystem,tinyformat}
#   (e.g. what the search tool's `fetch github:wjakob/layerlab` returns). Sources go to /tmp/layerlab and
#   /tmp/layerlab-ext, the build to BUILD_DIR (default /tmp/build-layerlab); about 3.5 minutes at -j1.
set -eu
LL=$1 FS=$2 TF=$3 B=${4:-/tmp/build-layerlab}
HERE=$(cd "$(dirname "$0")" && pwd)
LL_COMMIT=3e5257e3076a7287d1da9bbd4ee3f05fe37d3ee3      # layerlab HEAD (2017-11-09), the one measured
FS_COMMIT=0a539a6c988dc8691af317e077893e831dee2908      # ext/filesystem as layerlab pins it
TF_COMMIT=635345c75bd95891ee041ac51ce74ebc891d5bab      # ext/tinyformat as layerlab pins it
apt-get install -y libeigen3-dev pybind11-dev libtbb-dev libfftw3-dev python3-dev cmake ninja-build
rm -rf /tmp/layerlab /tmp/layerlab-ext
mkdir -p /tmp/layerlab /tmp/layerlab-ext/filesystem /tmp/layerlab-ext/tinyformat
git --git-dir="$LL" archive "$LL_COMMIT" | tar -x -C /tmp/layerlab
git --git-dir="$FS" archive "$FS_COMMIT" | tar -x -C /tmp/layerlab-ext/filesystem
git --git-dir="$TF" archive "$TF_COMMIT" | tar -x -C /tmp/layerlab-ext/tinyformat
cmake -S "$HERE" -B "$B" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3 \
      -DLAYERLAB_SOURCE_DIR=/tmp/layerlab -DLAYERLAB_EXT_DIR=/tmp/layerlab-ext
nice -n 15 ninja -C "$B" -j1
echo "built: $(ls "$B"/layerlab*.so)   (use: PYTHONPATH=$B /usr/bin/python3 -c 'import layerlab')"
