#!/usr/bin/env bash
# The shared library exports exactly the functions its public headers declare with FT_API, and every
# declared function is exported. Usage: scripts/check-exports.sh BUILD_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
lib=$(ls "${1:-build}"/libfracterra.so.* 2>/dev/null | head -n 1)
[ -n "$lib" ] || { echo "check-exports: no libfracterra.so.* in ${1:-build}" >&2; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# the linker's own symbols and OpenMP's named critical sections (.gomp_critical_user_*) are not API
nm -D --defined-only "$lib" | awk '$2 ~ /^[TDBRVW]$/ {print $3}' |
    grep -vE '^(__bss_start|_edata|_end|\.gomp_critical_user_.*)$' | sort -u >"$tmp/exported"
ls include/fracterra/*.h | grep -v '/export.h$' | xargs cat | tr '\n' ' ' | grep -oE 'FT_API[^(;{]*\(' | grep -oE '[A-Za-z_][A-Za-z0-9_]*[[:space:]]*\($' |
    tr -d ' (' | sort -u >"$tmp/declared"
extra=$(comm -23 "$tmp/exported" "$tmp/declared")
missing=$(comm -13 "$tmp/exported" "$tmp/declared")
if [ -n "$extra$missing" ]; then
    [ -n "$extra" ] && { echo "check-exports: exported but not declared with FT_API:"; echo "$extra" | sed 's/^/  /'; }
    [ -n "$missing" ] && { echo "check-exports: declared with FT_API but not exported:"; echo "$missing" | sed 's/^/  /'; }
    exit 1
fi
echo "check-exports: $(wc -l <"$tmp/exported") symbols, all declared in include/fracterra/*.h"
