#!/usr/bin/env bash
# End-to-end tests of the `tessera` CLI, one case per ctest test: cli_test.sh CASE TESSERA WORKDIR
set -euo pipefail
case_name=$1; tessera=$2; work=$3/$1
rm -rf "$work"; mkdir -p "$work"; cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
json_field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval('d'+sys.argv[2]))" "$1" "$2"; }

case "$case_name" in
  demo_writes_report_and_images)
    "$tessera" demo -o demo --threads 2 > stdout.json
    for f in report.json index.html fill_fan.png city_block.png city_ids.exr city_ids.a1.exr city_block.tframe; do
      [ -s "demo/$f" ] || fail "demo did not write $f"
    done
    [ "$(json_field demo/report.json "['bit_identical_1_vs_n_threads']")" = "True" ] || fail "thread check failed"
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
    ;;
  *) fail "unknown case $case_name" ;;
esac
echo "ok: $case_name"
