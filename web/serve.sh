#!/usr/bin/env bash
# Serves the page built by web/build.sh at http://127.0.0.1:${PORT:-8000}/
# with Python's static file server (it sends .wasm as application/wasm,
# which WebAssembly's streaming compile requires). Any static web host
# serves the same folder.
set -euo pipefail
dist="$(dirname "$0")/dist"
if [ ! -f "$dist/index.html" ]; then
    echo "web/serve.sh: no page built yet: run web/build.sh first" >&2
    exit 1
fi
echo "serving $dist at http://127.0.0.1:${PORT:-8000}/ (Ctrl-C stops)"
exec python3 -m http.server --bind 127.0.0.1 --directory "$dist" "${PORT:-8000}"
