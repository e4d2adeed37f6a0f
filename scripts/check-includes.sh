#!/usr/bin/env bash
# The part boundaries of docs/architecture.md, checked on every #include of the tree:
#   include/fracterra/  includes only its own headers;
#   cli/                includes the public headers ("fracterra/...") and its own headers, nothing of src/;
#   src/<part>/         includes the public headers, src/internal.h, its own part's headers, and of another
#                       part only the headers that part offers: <part>/<part>_shared.h or a service part's
#                       header (fft/fft.h);
#   GDAL/OGR/CPL headers only in src/io/ (and the CLI, which is a GDAL host); cairo only in src/render/.
# Usage: scripts/check-includes.sh [ROOT]. Prints each breach as FILE:LINE: reason and exits 1 if any.
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"

SERVICE_HEADERS="fft/fft.h"
bad=0
breach() { echo "$1: $2"; bad=1; }

# Quoted includes: FILE LINE HEADER per line.
quoted() { grep -Hn '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$@" 2>/dev/null |
           sed -E 's/^([^:]+):([0-9]+):.*"([^"]+)".*/\1 \2 \3/'; }
angled() { grep -Hn '^[[:space:]]*#[[:space:]]*include[[:space:]]*<' "$@" 2>/dev/null |
           sed -E 's/^([^:]+):([0-9]+):.*<([^>]+)>.*/\1 \2 \3/'; }

while read -r file line hdr; do
    [ -e "include/fracterra/$hdr" ] || [[ "$hdr" == fracterra/* ]] ||
        breach "$file:$line" "public header includes \"$hdr\", not a public header"
done < <(quoted include/fracterra/*.h include/fracterra/*.h.in)

while read -r file line hdr; do
    case "$hdr" in
        fracterra/*) ;;
        */*|internal.h) breach "$file:$line" "the CLI includes \"$hdr\": only include/ (\"fracterra/...\") and cli/ headers" ;;
        *) [ -e "cli/$hdr" ] || breach "$file:$line" "the CLI includes \"$hdr\", which is not in cli/" ;;
    esac
done < <(quoted cli/*.c cli/*.h)

while read -r file line hdr; do
    part=$(echo "$file" | cut -d/ -f2)
    case "$hdr" in
        fracterra/*|internal.h) continue ;;
    esac
    if [[ "$hdr" != */* ]]; then
        [ -e "src/$part/$hdr" ] || breach "$file:$line" "\"$hdr\" is not a header of src/$part/"
        continue
    fi
    hpart=${hdr%%/*}
    [ "$hpart" = "$part" ] && continue
    case " $SERVICE_HEADERS " in *" $hdr "*) continue ;; esac
    [ "$hdr" = "$hpart/${hpart}_shared.h" ] && continue
    breach "$file:$line" "src/$part includes \"$hdr\", a private header of src/$hpart (use $hpart/${hpart}_shared.h)"
done < <(quoted $(find src -name '*.c' -o -name '*.h'))

while read -r file line hdr; do
    part=$(echo "$file" | cut -d/ -f2)
    case "$hdr" in
        gdal*.h|ogr*.h|cpl_*.h) [ "$part" = io ] ||
            breach "$file:$line" "<$hdr> outside src/io: domain code never calls GDAL/OGR" ;;
        cairo*.h|cairo/*) [ "$part" = render ] ||
            breach "$file:$line" "<$hdr> outside src/render" ;;
    esac
done < <(angled $(find src -name '*.c' -o -name '*.h'))

if [ "$bad" = 0 ]; then
    echo "check-includes: the parts include only what docs/architecture.md allows"
fi
exit "$bad"
