#!/usr/bin/env bash
# Screenshot one page of the built book with headless Chromium (a developer
# check that formulas render as maths and figures show; CI does not need it).
#
#   scripts/screenshot.sh PAGE OUT.png [WIDTHxHEIGHT]
#
# PAGE is relative to book/_build/html (e.g. intro.html, levelset.html).
# The page is served from localhost by python's http.server, so it loads the
# book's local MathJax exactly as a web server would.  Needs Debian's chromium:
#   apt-get update && apt-get install -y chromium
set -euo pipefail

if [[ $# -lt 2 ]]; then
    echo "usage: $0 PAGE OUT.png [WIDTHxHEIGHT]" >&2
    exit 2
fi
PAGE=$1
OUT=$(realpath -m "$2")
SIZE=${3:-1200x1600}
HTML=${BOOK_HTML:-book/_build/html}
CHROMIUM=${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}

[[ -n "$CHROMIUM" ]] || { echo "screenshot: chromium not found" >&2; exit 1; }
[[ -f "$HTML/$PAGE" ]] || { echo "screenshot: $HTML/$PAGE not found (make book first)" >&2; exit 1; }

mkdir -p "$(dirname "$OUT")"
PY=${PYTHON:-python3}
PORT=$("$PY" -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
"$PY" -m http.server "$PORT" --bind 127.0.0.1 --directory "$HTML" >/dev/null 2>&1 &
server=$!
profile=$(mktemp -d)
trap 'kill "$server" 2>/dev/null || true; rm -rf "$profile"' EXIT
for _ in $(seq 50); do
    "$PY" -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$PORT/')" \
        2>/dev/null && break
    sleep 0.1
done

"$CHROMIUM" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --hide-scrollbars \
    --window-size="${SIZE/x/,}" --virtual-time-budget=10000 \
    --screenshot="$OUT" "http://127.0.0.1:$PORT/$PAGE" 2>/dev/null
[[ -s "$OUT" ]] || { echo "screenshot: chromium wrote no $OUT" >&2; exit 1; }
echo "screenshot: $OUT"
