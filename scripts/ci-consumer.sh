#!/usr/bin/env bash
# Installs a built tree into a scratch prefix and builds against the installed copy only, as a user would:
#  - docs/api.md's minimal program (count_valid.c), through pkg-config and through find_package(fracterra),
#    linked to the shared and to the static library, compiled as C and as C++, each run on the bundled DEM;
#  - a 3-line program calling ft_terrain_synth linked statically through `pkg-config --static` (fftw3f);
#  - `import fracterra` with Debian's /usr/bin/python3 from the installed package, outside the source tree.
# Usage: scripts/ci-consumer.sh [BUILD_DIR]   (default: build; it must have been built)
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:-build}" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"
cc="${CC:-cc}"
cxx="${CXX:-c++}"
dem="$src/tests/data/dem_luxembourg_terra_30s.tif"
want="4608 of 8550 cells valid"

fail() { echo "ci-consumer: $*" >&2; exit 1; }

echo "ci-consumer: install to $prefix"
cmake --install "$build" --prefix "$prefix" >/dev/null
libdir="$(dirname "$(find "$prefix" -name libfracterra.a | head -1)")"
[ -f "$libdir/libfracterra.a" ] || fail "no libfracterra.a under $prefix"
[ -f "$prefix/include/fracterra/version.h" ] || fail "version.h not installed"
export PKG_CONFIG_PATH="$libdir/pkgconfig"

# docs/api.md's count_valid.c: the C block after the line naming it.
awk '/^`count_valid.c`/ {f = 1; next} f && /^```c$/ {p = 1; next} p && /^```$/ {exit} p' "$src/docs/api.md" \
    > "$work/count_valid.c"
grep -q "ft_io_read_grid" "$work/count_valid.c" || fail "could not extract count_valid.c from docs/api.md"
cp "$work/count_valid.c" "$work/count_valid.cpp"

check_run() { # name exe
    local out
    out="$("$2" "$dem")" || fail "$1: exit status $?"
    [ "$out" = "$want" ] || fail "$1: printed '$out', expected '$want'"
    echo "ci-consumer: $1 ok ($out)"
}
not_shared() { # exe: must not need libfracterra.so
    if ldd "$1" | grep -q "libfracterra.so"; then fail "$1 is linked to libfracterra.so, not the static library"; fi
}

# pkg-config, shared and static, C and C++
cflags="$(pkg-config --cflags fracterra)"
libs="$(pkg-config --libs fracterra)"
static_libs="$(pkg-config --static --libs fracterra | sed "s#-lfracterra#$libdir/libfracterra.a#")"
# shellcheck disable=SC2086
{
    "$cc" -std=c11 "$work/count_valid.c" $cflags $libs -Wl,-rpath,"$libdir" -o "$work/pc_c_shared"
    "$cc" -std=c11 "$work/count_valid.c" $cflags $static_libs -o "$work/pc_c_static"
    "$cxx" -std=c++17 "$work/count_valid.cpp" $cflags $libs -Wl,-rpath,"$libdir" -o "$work/pc_cxx_shared"
    "$cxx" -std=c++17 "$work/count_valid.cpp" $cflags $static_libs -o "$work/pc_cxx_static"
}
not_shared "$work/pc_c_static"
not_shared "$work/pc_cxx_static"
for e in pc_c_shared pc_c_static pc_cxx_shared pc_cxx_static; do check_run "pkg-config $e" "$work/$e"; done

# The issue's 3-line program: FFTW single precision must come with pkg-config --static.
cat > "$work/synth.c" <<'C'
#include <fracterra/fracterra.h>
int main(void) { ft_grid *g = NULL; int rc = ft_terrain_synth(64, 64, NULL, &g); ft_grid_free(g); return rc != FT_OK; }
C
# shellcheck disable=SC2086
"$cc" -std=c11 "$work/synth.c" $cflags $static_libs -o "$work/synth_static" || fail "static link of ft_terrain_synth"
not_shared "$work/synth_static"
"$work/synth_static" || fail "synth_static failed"
echo "ci-consumer: pkg-config --static ft_terrain_synth ok"

# find_package(fracterra): fracterra::fracterra and fracterra::fracterra_static, C and C++
mkdir -p "$work/cm"
cp "$work/count_valid.c" "$work/count_valid.cpp" "$work/cm/"
cat > "$work/cm/CMakeLists.txt" <<'CM'
cmake_minimum_required(VERSION 3.18)
project(consumer LANGUAGES C CXX)
find_package(fracterra 0.1 REQUIRED)
add_executable(cm_c_shared count_valid.c)
target_link_libraries(cm_c_shared PRIVATE fracterra::fracterra)
add_executable(cm_c_static count_valid.c)
target_link_libraries(cm_c_static PRIVATE fracterra::fracterra_static)
add_executable(cm_cxx_shared count_valid.cpp)
target_link_libraries(cm_cxx_shared PRIVATE fracterra::fracterra)
add_executable(cm_cxx_static count_valid.cpp)
target_link_libraries(cm_cxx_static PRIVATE fracterra::fracterra_static)
CM
cmake -S "$work/cm" -B "$work/cm/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/cm/build" -j 2 >/dev/null || fail "find_package consumer build failed"
not_shared "$work/cm/build/cm_c_static"
not_shared "$work/cm/build/cm_cxx_static"
for e in cm_c_shared cm_c_static cm_cxx_shared cm_cxx_static; do check_run "find_package $e" "$work/cm/build/$e"; done

# import fracterra from the installed package: no FRACTERRA_LIBRARY, outside the source tree.
pydir="$(dirname "$(find "$prefix" -path '*-packages/fracterra/__init__.py' | head -1)")"
[ -f "$pydir/_install_config.py" ] || fail "the Python package or its _install_config.py is not installed"
loaded="$(cd "$work" && env -u FRACTERRA_LIBRARY PYTHONPATH="$(dirname "$pydir")" /usr/bin/python3 -c \
    'import fracterra; g = fracterra.read_grid("'"$dem"'"); print(fracterra.library_path, int(g.mask.sum()))')"
case "$loaded" in
    "$libdir"/libfracterra.so*" 4608") echo "ci-consumer: import fracterra ok ($loaded)" ;;
    *) fail "import fracterra loaded '$loaded', expected $libdir/libfracterra.so.* and 4608 valid cells" ;;
esac
echo "ci-consumer: all consumer builds pass"
