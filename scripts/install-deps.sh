#!/usr/bin/env bash
# Installs the Debian packages fracterra needs to build, test and run its demo and bench, and only those
# that are missing. Idempotent; needs root (or sudo) only when something is missing.
#   --peers   also the peer tools `make bench` compares against when they are installed: GRASS GIS
#             (r.surf.fractal, r.surf.contour, v.surf.rst) and Gwyddion's libraries (its fractal estimators,
#             linked into the bench at configure time: re-run cmake after installing them).
set -euo pipefail

peers=0
for arg in "$@"; do
  case "$arg" in
    --peers) peers=1 ;;
    -h|--help) echo "usage: scripts/install-deps.sh [--peers]"; exit 0 ;;
    *) echo "install-deps: unknown option '$arg' (usage: scripts/install-deps.sh [--peers])" >&2; exit 2 ;;
  esac
done

packages=(
  build-essential cmake pkg-config
  libgdal-dev gdal-bin        # raster/vector I/O; gdal-bin gives gdalinfo/ogrinfo/gdal_translate (tests, bench peers)
  libgeos-dev                 # robust polygon operations
  libfftw3-dev                # FFT
  libgsl-dev                  # RNG, statistics, least squares
  libcairo2-dev               # PNG/SVG/PDF rendering
  libjson-c-dev               # JSON output
  libtiff-dev libzstd-dev     # GeoTIFF tiles compressed on fracterra's threads (src/io/gtiff_tiles.c)
  libcmocka-dev               # unit tests
  python3-numpy python3-gdal  # the Python package (python/fracterra): NumPy arrays, osgeo.gdal helpers
  python3-pytest python3-dask # its tests (make test), and the dask example
  libproj-dev                 # PROJ geodesic.h: reference ellipsoidal lengths in the tests (pulled in by GDAL too)
  clang libclang-rt-dev libomp-dev  # make fuzz: libFuzzer harnesses (clang's runtime, OpenMP for clang)
  libopenmpi-dev openmpi-bin  # MPI: mpiexec -n N fracterra dim map|dim surface (docs/tiling.md), its tests
  libfftw3-mpi-dev            # FFTW MPI transforms: mpiexec -n N fracterra synth --method fft (docs/tiling.md)
)
if [ "$peers" -eq 1 ]; then
  packages+=(
    grass-core                  # bench peers: r.surf.fractal, r.surf.contour, v.surf.rst
    gwyddion libgwyddion20-dev  # bench peers: gwy_data_field_fractal_* (partitioning, cube counting, ...)
  )
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "install-deps: need root to install: ${missing[*]}" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
