#!/bin/sh
# Regenerates the GL reference renders of this folder (NAME.ids.png and
# NAME.depth.png for every case of cases.txt) with the peers/ harness,
# which draws them with Mesa's llvmpipe through OSMesa
# (apt-get install -y libosmesa6-dev).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
cargo run --release --manifest-path "$root/peers/Cargo.toml" -- --reference "$here"
