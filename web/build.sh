#!/usr/bin/env bash
# Builds the explorable page into web/dist: the hider-web crate for
# wasm32-unknown-unknown (release), its JavaScript bindings (wasm-bindgen,
# the CLI at the version Cargo.lock pins for the wasm-bindgen crate), the
# static files and the bundled models. Installs what is missing: the
# wasm32 target (rustup) and wasm-bindgen-cli (cargo install).
# Serve the result with: python3 -m http.server -d web/dist 8000
set -euo pipefail
cd "$(dirname "$0")/.."

version="$(awk '/^name = "wasm-bindgen"$/ {getline; gsub(/"/, "", $3); print $3; exit}' Cargo.lock)"
if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
    echo "== installing the wasm32-unknown-unknown target (rustup)"
    rustup target add wasm32-unknown-unknown
fi
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')" != "$version" ]; then
    # Only the wasm-bindgen binary, without the test runner's TLS stack
    # (rustls and ring): about 2 minutes on 2 cores instead of many more.
    echo "== installing wasm-bindgen-cli $version (cargo install, about 2 minutes)"
    cargo install wasm-bindgen-cli --version "$version" --no-default-features --bin wasm-bindgen
fi

echo "== cargo build --release --target wasm32-unknown-unknown -p hider-web"
cargo build --release --locked --target wasm32-unknown-unknown -p hider-web

dist=web/dist
rm -rf "$dist"
mkdir -p "$dist/assets/spider"
wasm-bindgen --target web --no-typescript --out-dir "$dist/pkg" \
    target/wasm32-unknown-unknown/release/hider_web.wasm
if command -v wasm-opt >/dev/null 2>&1; then
    wasm-opt -O2 "$dist/pkg/hider_web_bg.wasm" -o "$dist/pkg/hider_web_bg.wasm"
fi
cp web/static/* "$dist/"
cp assets/*.obj assets/*.mtl assets/*.png "$dist/assets/"
cp assets/spider/* "$dist/assets/spider/"
echo "== built $dist ($(du -sh "$dist" | cut -f1)); serve it with web/serve.sh"
