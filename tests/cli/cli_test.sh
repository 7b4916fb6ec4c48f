#!/usr/bin/env bash
# End-to-end tests of the `tessera` CLI, one case per ctest test: cli_test.sh CASE TESSERA WORKDIR
set -euo pipefail
case_name=$1; tessera=$2; work=$3/$1
src=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$work"; mkdir -p "$work"; cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
json_field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval('d'+sys.argv[2]))" "$1" "$2"; }

case "$case_name" in
  demo_writes_report_and_images)
    "$tessera" demo -o demo --threads 2 --railway "$src/data/railway.glb" > stdout.json
    for f in report.json index.html fill_fan.png city_block.png city_ids.exr city_ids.a1.exr city_block.tframe \
             mta/render/plot.png mta/runs/runs.png mta/texel/histogram.png mta/render/frames.json; do
      [ -s "demo/$f" ] || fail "demo did not write $f"
    done
    [ "$(json_field demo/report.json "['bit_identical_1_vs_n_threads']")" = "True" ] || fail "thread check failed"
    [ "$(json_field demo/report.json "['atlas_tree']['texel']['magnification_violations_when_every_needed_block_resident']")" = "0" ] \
      || fail "the demo's atlas tree magnifies beyond tau"
    ;;
  replay_matches_render)
    "$tessera" render texture_array --threads 2 -o a.png --stats a.json --record a.tframe > /dev/null
    "$tessera" replay a.tframe --threads 1 -o b.png --stats b.json > /dev/null
    [ "$(json_field a.json "['image_sha256']")" = "$(json_field b.json "['image_sha256']")" ] || fail "replay differs"
    cmp -s a.png b.png || fail "PNG files differ"
    ;;
  image_sha256_is_the_hash_of_the_decoded_png)
    "$tessera" render blend -o img.png --stats s.json > /dev/null
    want=$(json_field s.json "['image_sha256']")
    got=$(python3 - <<'PY'
import hashlib, zlib, struct
data = open('img.png','rb').read()
pos, idat, w, h = 8, b'', 0, 0
while pos < len(data):
    n, t = struct.unpack('>I4s', data[pos:pos+8]); body = data[pos+8:pos+8+n]
    if t == b'IHDR': w, h, bd, ct = struct.unpack('>IIBB', body[:10]); assert bd == 8 and ct == 6
    if t == b'IDAT': idat += body
    pos += 12 + n
raw, bpp, stride = zlib.decompress(idat), 4, w * 4
out, prev, i = bytearray(), bytearray(stride), 0
for y in range(h):
    f = raw[i]; line = bytearray(raw[i+1:i+1+stride]); i += 1 + stride
    for x in range(stride):
        a = line[x-bpp] if x >= bpp else 0; b = prev[x]; c = prev[x-bpp] if x >= bpp else 0
        if f == 1: line[x] = (line[x] + a) & 255
        elif f == 2: line[x] = (line[x] + b) & 255
        elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c; pa, pb, pc = abs(p-a), abs(p-b), abs(p-c)
            line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    out += line; prev = line
print(hashlib.sha256(bytes(out)).hexdigest())
PY
)
    [ "$want" = "$got" ] || fail "image_sha256 $want != sha256 of decoded PNG $got"
    ;;
  unknown_scene_is_a_clear_error)
    if "$tessera" render no_such_scene 2> err.txt; then fail "accepted an unknown scene"; fi
    grep -q "unknown scene 'no_such_scene' (known: fill_fan" err.txt || fail "message: $(cat err.txt)"
    ;;
  bad_size_is_a_clear_error)
    if "$tessera" render blend --size 12y4 2> err.txt; then fail "accepted a bad size"; fi
    grep -q -- "--size '12y4'" err.txt || fail "message: $(cat err.txt)"
    ;;
  truncated_frame_is_a_clear_error)
    "$tessera" render depth --record f.tframe > /dev/null
    head -c 300 f.tframe > cut.tframe
    if "$tessera" replay cut.tframe 2> err.txt; then fail "accepted a truncated frame"; fi
    grep -q "cut.tframe" err.txt || fail "message does not name the file: $(cat err.txt)"
    ! grep -qi "internal error" err.txt || fail "crashed into an internal error: $(cat err.txt)"
    ;;
  missing_output_directory_leaves_nothing)
    if "$tessera" render depth -o nodir/x.png 2> err.txt; then fail "wrote into a missing directory"; fi
    grep -q "nodir/x.png" err.txt || fail "message: $(cat err.txt)"
    [ -z "$(ls -A . | grep -v err.txt)" ] || fail "left files behind: $(ls -A)"
    ;;
  help_explains_every_command)
    "$tessera" --help > help.txt
    for c in scenes render replay validate golden demo; do grep -q "$c" help.txt || fail "--help lacks $c"; done
    "$tessera" render --help | grep -q -- "--record" || fail "render --help lacks --record"
    ;;
  city_and_atlas_tree_build_end_to_end)
    "$tessera" city --preset berlin --buildings 6 --seed 3 -o city --quiet > city.json
    gltf=$(ls city/*.gltf | head -1)
    [ -n "$gltf" ] || fail "no .gltf written"
    "$tessera" mta build "$gltf" -o tree.mta --d-min 50 --quiet > build.json
    "$tessera" mta info tree.mta > info.json 2> /dev/null
    [ "$(json_field info.json "['triangles']")" -ge 1 ] || fail "info reports no triangles"
    [ "$(json_field info.json "['blocks']['atlas']['count']")" -ge 1 ] || fail "info reports no atlas blocks"
    ;;
  corrupted_atlas_tree_is_a_clear_error)
    "$tessera" city --preset berlin --buildings 4 -o city --quiet > /dev/null
    "$tessera" mta build "$(ls city/*.gltf | head -1)" -o tree.mta --d-min 50 --quiet > /dev/null
    size=$(stat -c %s tree.mta)
    head -c $((size / 2)) tree.mta > cut.mta
    if "$tessera" mta info cut.mta > /dev/null 2> err.txt; then fail "accepted a truncated tree"; fi
    grep -q "cut.mta" err.txt || fail "message does not name the file: $(cat err.txt)"
    ! grep -qi "internal error" err.txt || fail "crashed: $(cat err.txt)"
    # Issue 9, item 1: the root's four child indices set to -5 and both checksums recomputed. `mta info`
    # accepted it and `mta render` wrote out of bounds; every command must refuse it on open.
    python3 - tree.mta neg.mta <<'PY'
import hashlib, struct, sys
b = bytearray(open(sys.argv[1], 'rb').read())
meta = struct.unpack_from('<Q', b, 24)[0]
p = meta + 4 * 4 + 6 * 8 + 5 * 8 + 4 + 3 * 8             # parameters, stats (docs/mta-format.md)
n, = struct.unpack_from('<I', b, p); p += 4 + 6 * n        # textures
n, = struct.unpack_from('<I', b, p); p += 4
for _ in range(n):                                         # images: 5 u32, then the name
    k, = struct.unpack_from('<I', b, p + 20); p += 24 + k
n, = struct.unpack_from('<Q', b, p); p += 8 + 24 * n       # pieces
n, = struct.unpack_from('<Q', b, p); p += 8 + 56 * n       # blocks
p += 4 + 1 + 8                                             # tree count, alpha, node count
struct.pack_into('<4i', b, p + 44, -5, -5, -5, -5)         # node 0: 44 bytes of bounds ... cell, then children
b[40:72] = hashlib.sha256(bytes(b[meta:])).digest()
b[96:128] = hashlib.sha256(bytes(b[:96])).digest()
open(sys.argv[2], 'wb').write(b)
PY
    for cmd in "mta info neg.mta" "mta render neg.mta --frames 2 --size 64x48 -o render --quiet" \
               "mta runs neg.mta --frames 2 --size 64x48 -o runs --quiet" "texel neg.mta --frames 2 --size 64x48 -o texel --quiet"; do
      rc=0
      # shellcheck disable=SC2086  # $cmd is split into the command's words on purpose
      "$tessera" $cmd > /dev/null 2> err.txt || rc=$?
      [ "$rc" -eq 2 ] || fail "'$cmd' exited with $rc, not 2: $(cat err.txt)"
      grep -q "neg.mta: trees\[0\].nodes\[0\].children\[0\]: -5 is neither -1" err.txt || fail "'$cmd': $(cat err.txt)"
    done
    ;;
  atlas_tree_goldens_reproduce_bit_exactly)
    # Includes the built-in scenes; the railway frames render data/railway.glb.
    "$tessera" golden check --dir "$src/golden" --railway "$src/data/railway.glb" > check.json \
      || fail "golden check failed: $(cat check.json)"
    [ "$(json_field check.json "['passed']")" -ge 16 ] || fail "fewer goldens than expected: $(cat check.json)"
    ;;
  railway_golden_command_reproduces_the_golden_frames)
    # The manifest's "command" of the mta_railway entries, run with the CLI, gives the golden frames
    # (golden/railway_frames.cpp lays out the path and the options itself).
    "$tessera" mta build "$src/data/railway.glb" --d-min 5 -o tree.mta --quiet > /dev/null
    "$tessera" mta render tree.mta --path thesis --frames 60 --size 256x192 --capacity 48 --budget 4MiB --save-every 15 \
      -o render --quiet > /dev/null
    for i in 0 15 30 45 59; do
      "$tessera" compare "$src/golden/images/mta_railway.f$(printf %03d $i).png" "render/frame_$(printf %04d $i).png" \
        > compare.json || fail "frame $i differs from its golden: $(cat compare.json)"
    done
    ;;
  atlas_tree_render_runs_and_texel_end_to_end)
    "$tessera" city --preset berlin --buildings 9 --seed 5 -o city --quiet > /dev/null
    "$tessera" mta build city/*.gltf -o tree.mta --d-min 40 --quiet > /dev/null
    "$tessera" mta render tree.mta --frames 40 --size 160x120 --capacity 8 --budget 2blocks --save-every 20 -o render --quiet > render.json
    for f in frames.json plot.png frame_0000.png frame_0020.png frame_0039.png; do [ -s "render/$f" ] || fail "render did not write $f"; done
    python3 - render/frames.json <<'PY' || fail "frames.json is inconsistent"
import json, sys
d = json.load(open(sys.argv[1]))
assert len(d["frames"]) == 40
for f in d["frames"]:
    for k in ("texture_binds", "texture_state_changes", "draw_calls", "nodes_with_atlas", "nodes_with_original_textures",
              "blocks_resident", "bytes_resident", "capacity_bytes", "blocks_loaded", "frame_time_ms"):
        assert k in f, k
    assert f["bytes_resident"] <= f["capacity_bytes"]
assert d["summary"]["peak_bytes_resident"] <= d["summary"]["capacity_bytes"]
PY
    # Same path and budget, another thread count: the same frames.
    "$tessera" mta render tree.mta --frames 40 --size 160x120 --capacity 8 --budget 2blocks --save-every 0 --threads 1 -o render1 --quiet > /dev/null
    python3 -c "import json,sys; a,b=[[f['image_sha256'] for f in json.load(open(p))['frames']] for p in sys.argv[1:]]; assert a==b" \
      render/frames.json render1/frames.json || fail "frames differ between thread counts"
    "$tessera" texel tree.mta --frames 20 --size 160x120 --budget unlimited --capacity 512 --save-every 10 -o texel --quiet > texel.json
    [ "$(json_field texel.json "['magnification_violations_when_every_needed_block_resident']")" = "0" ] || fail "violations: $(cat texel.json)"
    for f in texel.json histogram.png texel_0000.png texel_0019.png; do [ -s "texel/$f" ] || fail "texel did not write $f"; done
    "$tessera" mta runs tree.mta --frames 12 --size 128x96 --save-every 0 -o runs --quiet > runs.json
    for m in original dummy atlas_tree; do
      [ "$(json_field runs.json "['$m']['draw_calls_max']")" != "" ] || fail "runs lacks $m"
    done
    [ -s runs/runs.png ] || fail "runs did not write runs.png"
    ;;
  bad_camera_path_is_a_clear_error)
    "$tessera" city --preset berlin --buildings 4 -o city --quiet > /dev/null
    "$tessera" mta build city/*.gltf -o tree.mta --d-min 50 --quiet > /dev/null
    printf 'tessera-camera-path 1\n0 1 2 3 4\n' > bad.path
    if "$tessera" mta render tree.mta --path bad.path -o out --quiet > /dev/null 2> err.txt; then fail "accepted a bad path"; fi
    grep -q "bad.path:2" err.txt || fail "message does not name file and line: $(cat err.txt)"
    if "$tessera" mta render tree.mta --budget 3furlongs -o out --quiet > /dev/null 2> err2.txt; then fail "accepted a bad budget"; fi
    grep -q -- "--budget" err2.txt || fail "message does not name the option: $(cat err2.txt)"
    ;;
  interrupted_build_leaves_no_temporary)
    # SIGTERM mid-write: exit 143, the temporary is gone, the previous output is intact.
    printf 'previous output' > tree.mta
    wait_for_temporary() {  # until the build's temporary exists and holds more than its header
      for _ in $(seq 1200); do
        t=$(ls tree.mta.tmp-* 2>/dev/null | head -1 || true)
        if [ -n "$t" ] && [ "$(stat -c %s "$t" 2>/dev/null || echo 0)" -gt 200000 ]; then return 0; fi
        sleep 0.1
      done
      fail "the build never started writing"
    }
    "$tessera" mta build "$src/data/railway.glb" -o tree.mta --quiet > /dev/null 2>&1 & pid=$!
    wait_for_temporary
    kill -TERM "$pid"
    rc=0; wait "$pid" || rc=$?
    [ "$rc" = 143 ] || fail "SIGTERM: exit status $rc, expected 143"
    ls tree.mta.tmp-* > /dev/null 2>&1 && fail "SIGTERM left a temporary: $(ls tree.mta.tmp-*)"
    [ "$(cat tree.mta)" = "previous output" ] || fail "SIGTERM damaged the previous output"
    # SIGKILL cannot be caught: the temporary stays until the next writer of tree.mta removes it.
    "$tessera" mta build "$src/data/railway.glb" -o tree.mta --quiet > /dev/null 2>&1 & pid=$!
    wait_for_temporary
    kill -KILL "$pid"
    wait "$pid" || true
    [ -e "tree.mta.tmp-$pid" ] || fail "expected the killed build's temporary tree.mta.tmp-$pid"
    [ "$(cat tree.mta)" = "previous output" ] || fail "SIGKILL damaged the previous output"
    "$tessera" city --preset berlin --buildings 4 -o city --quiet > /dev/null
    "$tessera" mta build city/*.gltf -o tree.mta --d-min 50 --quiet > /dev/null
    ls tree.mta.tmp-* > /dev/null 2>&1 && fail "the next build left the stale temporary: $(ls tree.mta.tmp-*)"
    "$tessera" mta info tree.mta > /dev/null || fail "the new tree.mta is not valid"
    ;;
  *) fail "unknown case $case_name" ;;
esac
echo "ok: $case_name"
