#!/usr/bin/env bash
# Time and peak memory of large textures (the table in docs/textures.md):
# one 8000 x 8000 RGBA PNG on one triangle at 64 px, and six of them (six
# files) under a 4 GB address-space limit (ulimit -v), which aborted before
# the mip levels and the texture budget.
#
#   cargo build --release -p hider-cli && bash tests/texture_memory.sh
#
# HIDER names the binary (default target/release/hider); needs python3 and
# GNU time (/usr/bin/time).
set -euo pipefail
HIDER=$(realpath "${HIDER:-target/release/hider}")
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
cd "$DIR"
python3 - <<'PY'
import struct, zlib
def png(path, w):
    # An opaque green disc on transparent red (a leaf card): RGBA, 8 bits.
    def chunk(t, d):
        return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
    co = zlib.compressobj(6)
    body = []
    c, r = w / 2, w * 0.4
    for y in range(w):
        dy = y + 0.5 - c
        if abs(dy) >= r:
            row = b'\xc8\x32\x32\x00' * w
        else:
            h = int((r * r - dy * dy) ** 0.5)
            a, b = int(c - h), int(c + h)
            row = b'\xc8\x32\x32\x00' * a + b'\x20\xc8\x40\xff' * (b - a) + b'\xc8\x32\x32\x00' * (w - b)
        body.append(co.compress(b'\x00' + row))
    body.append(co.flush())
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, w, 8, 6, 0, 0, 0))
                + chunk(b'IDAT', b''.join(body)) + chunk(b'IEND', b''))
png('t0.png', 8000)
PY
for k in 1 2 3 4 5; do cp t0.png "t$k.png"; done
printf 'newmtl m\nKd 1 1 1\nmap_Kd t0.png\n' > one.mtl
printf 'mtllib one.mtl\nusemtl m\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0.5 1\nf 1/1 2/2 3/3\n' > one.obj
{
    echo "mtllib six.mtl"
    echo "vt 0 0"; echo "vt 1 0"; echo "vt 1 1"; echo "vt 0 1"
    for k in 0 1 2 3 4 5; do
        x=$((k * 2 - 6))
        echo "usemtl m$k"
        echo "v $x -1 0"; echo "v $((x + 2)) -1 0"; echo "v $((x + 2)) 1 0"; echo "v $x 1 0"
        v=$((k * 4 + 1))
        echo "f $v/1 $((v + 1))/2 $((v + 2))/3"; echo "f $v/1 $((v + 2))/3 $((v + 3))/4"
    done
} > six.obj
for k in 0 1 2 3 4 5; do printf 'newmtl m%d\nKd 1 1 1\nmap_Kd t%d.png\n' "$k" "$k"; done > six.mtl
measure() {
    /usr/bin/time -v "$@" 2>time.txt >/dev/null || { tail -5 time.txt; return 1; }
    local wall cpu rss
    wall=$(grep 'Elapsed (wall clock)' time.txt | awk '{print $NF}')
    cpu=$(awk '/User time|System time/ {s += $NF} END {printf "%.2f", s}' time.txt)
    rss=$(grep 'Maximum resident' time.txt | awk '{print $NF}')
    echo "| $wall | $cpu s | $((rss / 1024)) MB |"
}
echo "| case | wall | CPU (user + sys) | max RSS |"
echo "|---|---|---|---|"
echo "| one 8000^2 RGBA texture, 1 triangle, 64 px $(measure "$HIDER" render one.obj --size 64 -o out.png)"
echo "| the same at 1024 px $(measure "$HIDER" render one.obj --size 1024 -o out.png)"
echo "| six 8000^2 textures, 64 px, ulimit -v 4 GB $(ulimit -v 4194304; measure "$HIDER" render six.obj --size 64 -o out.png)"
echo "| six 8000^2 textures, 1024 px, ulimit -v 4 GB $(ulimit -v 4194304; measure "$HIDER" render six.obj --size 1024 -o out.png)"
