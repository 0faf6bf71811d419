#!/usr/bin/env bash
# Fetch MathJax 3 from the npm registry into book/_mathjax/ so the book renders
# formulas offline (Jupyter Book 1 would otherwise load MathJax from a CDN).
#
#   scripts/fetch_mathjax.sh [DEST]      default DEST: book/_mathjax
#
# Result: DEST/mathjax/tex-chtml.js (+ the fonts and extensions it loads).
# book/_config.yml copies DEST into the built html (html_extra_path) and points
# mathjax_path at it.  DEST is git-ignored; the script does nothing if the file
# is already there.  Needs npm (Debian: apt-get install -y nodejs npm).
set -euo pipefail

VERSION=3.2.2
DEST=${1:-book/_mathjax}
TARGET="$DEST/mathjax"

if [[ -f "$TARGET/tex-chtml.js" ]]; then
    exit 0
fi
if ! command -v npm >/dev/null 2>&1; then
    echo "fetch_mathjax: npm not found; install it (apt-get install -y nodejs npm)" >&2
    exit 1
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "fetch_mathjax: npm pack mathjax@$VERSION"
(cd "$tmp" && npm pack --silent "mathjax@$VERSION" >/dev/null)
tar -xzf "$tmp/mathjax-$VERSION.tgz" -C "$tmp"

# es5/ holds the browser bundles (about 24 MB with fonts and extensions).
rm -rf "$TARGET"
mkdir -p "$DEST"
cp -r "$tmp/package/es5" "$TARGET"
cp "$tmp/package/LICENSE" "$TARGET/LICENSE"
echo "fetch_mathjax: installed $TARGET/tex-chtml.js ($(du -sh "$TARGET" | cut -f1))"
