#!/usr/bin/env bash
# End-to-end tests of the `tessera` CLI, one case per ctest test: cli_test.sh CASE TESSERA WORKDIR
set -euo pipefail
case_name=$1; tessera=$2; work=$3/$1
src=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$work"; mkdir -p "$work"; cd "$work"
# A passing case removes its work directory: the demo and atlas-tree cases write hundreds of MB, and
# two builds' worth of them filled the disk of a CI machine (stop 21). A failing case keeps it to look at.
trap 'rc=$?; cd /; if [ $rc = 0 ]; then rm -rf "$work"; else echo "kept for inspection: $work" >&2; fi' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
json_field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval('d'+sys.argv[2]))" "$1" "$2"; }
# refused STATUS TEXT COMMAND...: COMMAND exits with STATUS, says TEXT on stderr, and is no internal error.
refused() {
  local want=$1 text=$2; shift 2
  local rc=0; "$@" > refused.out 2> refused.err || rc=$?
  [ "$rc" = "$want" ] || fail "$*: exit status $rc, expected $want: $(cat refused.err)"
  grep -qF -- "$text" refused.err || fail "$*: the message lacks '$text': $(cat refused.err)"
  ! grep -qi "internal error" refused.err || fail "$*: $(cat refused.err)"
}

case "$case_name" in
  demo_writes_report_and_images)
    # The scenes half of the demo; demo_runs_the_atlas_tree_on_railway runs the other half, so that each
    # stays well inside its timeout in the ASan build on a loaded machine.
    "$tessera" demo -o demo --threads 2 --no-suite --no-mta --no-tab --no-rtta > stdout.json
    for f in report.json index.html fill_fan.png city_block.png city_ids.exr city_ids.a1.exr city_block.tframe; do
      [ -s "demo/$f" ] || fail "demo did not write $f"
    done
    [ "$(json_field demo/report.json "['bit_identical_1_vs_n_threads']")" = "True" ] || fail "thread check failed"
    ;;
  demo_runs_the_atlas_tree_on_railway)
    # The ASan build sets TESSERA_CLI_SANITIZED=1 (tests/CMakeLists.txt): there the same demo runs on a
    # generated six-building city, with the same checks. Its time went into re-uploading railway's textures
    # every frame (227 s, against 25 s in Release; CONTRIBUTING.md "CI"), and the sanitizers already see
    # railway.glb built and rendered by railway_golden_command_reproduces_the_golden_frames and
    # DrawOrder.OnRailway*, and the runs and the texel analysis by atlas_tree_render_runs_and_texel_end_to_end.
    # The Release run keeps railway.glb.
    model="$src/data/railway.glb"
    if [ "${TESSERA_CLI_SANITIZED:-0}" = 1 ]; then
      "$tessera" city --preset berlin --buildings 6 --seed 3 -o city --quiet > /dev/null
      model=city/berlin.gltf
    fi
    "$tessera" demo -o demo --threads 2 --no-gl --no-suite --no-thread-check --no-tab --no-rtta --railway "$model" > stdout.json
    for f in report.json index.html mta/render/plot.png mta/runs/runs.png mta/texel/histogram.png mta/render/frames.json; do
      [ -s "demo/$f" ] || fail "demo did not write $f"
    done
    [ "$(json_field demo/report.json "['atlas_tree']['texel']['magnification_violations_when_every_needed_block_resident']")" = "0" ] \
      || fail "the demo's atlas tree magnifies beyond tau"
    ;;
  demo_runs_texture_array_batching_on_railway)
    "$tessera" demo -o demo --threads 2 --no-gl --no-suite --no-thread-check --no-mta --no-rtta --railway "$src/data/railway.glb" > stdout.json
    for f in report.json index.html tab/railway.tab tab/render/plot.png tab/render/index.html tab/render/frames.json \
             tab/render/batched_0012.png tab/render/baseline_0012.tframe tab/render/diff_0012.png; do
      [ -s "demo/$f" ] || fail "demo did not write $f"
    done
    [ "$(json_field demo/report.json "['texture_array_batching']['render']['batched']['draw_calls_max']")" = "2.0" ] \
      || fail "railway is not drawn in two geometry batches"
    [ "$(json_field demo/report.json "['texture_array_batching']['render']['baseline']['draw_calls_max']")" = "33.0" ] \
      || fail "the baseline does not draw each of the 33 meshes"
    ;;
  demo_runs_render_to_texture_atlas)
    "$tessera" demo -o demo --threads 2 --no-gl --no-suite --no-thread-check --no-mta --no-tab --railway "$src/data/railway.glb" > stdout.json
    for f in report.json index.html rtta/five/index.html rtta/five/table.json rtta/five/rtta_0012.png rtta/five/atlas_l0_0012.png \
             rtta/five_ghosted/rtta_0001.png rtta/five_ghosted_ao/rtta_0001.png rtta/railway/rtta_0006.png rtta/railway/atlas_l0_0006.png; do
      [ -s "demo/$f" ] || fail "demo did not write $f"
    done
    [ "$(json_field demo/report.json "['render_to_texture_atlas']['railway']['object_count']")" = "33" ] || fail "railway is not 33 objects"
    grep -qF "Render-to-texture-atlas" demo/index.html || fail "the demo page has no RTTA section"
    ;;
  tab_build_info_render_end_to_end)
    "$tessera" tab build "$src/data/railway.glb" -o rw.tab --quiet > build.json
    [ "$(json_field build.json "['output_batches']")" = "2" ] || fail "railway at a_max 8 needs 2 output batches"
    [ "$(json_field build.json "['input_batches']")" = "33" ] || fail "railway has 33 input batches"
    "$tessera" tab build "$src/data/railway.glb" -o rw2.tab --quiet > /dev/null
    cmp -s rw.tab rw2.tab || fail "the same model gave different .tab bytes"
    "$tessera" tab info rw.tab > info.json
    [ "$(json_field info.json "['geometry_batches']")" = "2" ] || fail "tab info disagrees with tab build"
    "$tessera" tab render rw.tab --both --frames 4 --size 96x72 --save-every 2 -o r --quiet > summary.json
    for f in frames.json plot.png index.html batched_0000.png baseline_0000.png batched_0003.tframe diff_0002.png; do
      [ -s "r/$f" ] || fail "tab render did not write $f"
    done
    [ "$(json_field r/frames.json "['frames'][1]['variant']")" = "batched" ] || fail "frames.json rows lack the variant"
    [ "$(json_field r/frames.json "['frames'][1]['draw_calls']")" = "2" ] || fail "batched frame is not 2 draws"
    # A saved frame replays to the same image.
    "$tessera" replay r/batched_0003.tframe -o replay.png --stats replay.json > /dev/null
    [ "$(json_field replay.json "['image_sha256']")" = "$(json_field r/frames.json "['frames'][7]['image_sha256']")" ] \
      || fail "the saved batched frame does not replay to its image"
    ;;
  tab_golden_command_reproduces_the_golden_frames)
    # The manifest's command for tab_railway.fNNN, run through the CLI (with the .tab file round trip),
    # must give the golden pixels that golden/tab_railway_frames.cpp renders in memory.
    "$tessera" tab build "$src/data/railway.glb" -o railway.tab --quiet > /dev/null
    "$tessera" tab render railway.tab --path orbit --frames 24 --size 256x192 --save-every 8 -o r --quiet > /dev/null
    for f in 0 8 16 23; do
      want=$(json_field "$src/golden/manifest.json" "['tests']['tab_railway.f$(printf %03d $f)']['image_sha256']")
      got=$(python3 -c "import json; print([r for r in json.load(open('r/frames.json'))['frames'] if r['frame'] == $f][0]['image_sha256'])")
      [ "$want" = "$got" ] || fail "frame $f: $got, golden $want"
    done
    ;;
  rtta_render_end_to_end)
    "$tessera" rtta render five --frames 4 --size 96x72 --save-every 2 --border 2 -o r --quiet > table.json
    for f in frames.json table.json plot.png index.html std_0000.png rtt_0002.png rtta_0003.png atlas_l0_0000.png \
             rtta_0003.tframe rtt_0000.tframe std_0002.tframe; do
      [ -s "r/$f" ] || fail "rtta render did not write $f"
    done
    [ "$(json_field table.json "['object_count']")" = "5" ] || fail "the five-object scene is not 5 objects"
    [ "$(json_field table.json "['modes']['rtta']['render_target_changes_max']")" = "2.0" ] || fail "RTTA is not one atlas pass and one composite"
    [ "$(json_field table.json "['modes']['rtt']['render_target_changes_max']")" = "6.0" ] || fail "RTT is not one pass per object"
    [ "$(json_field table.json "['composite_vs_std']['rtt']['identical_percent_min']")" = "100.0" ] || fail "RTT depth sprites do not reproduce STD"
    [ "$(json_field table.json "['composite_vs_std']['rtta']['unexplained']")" = "0" ] \
      || fail "RTTA composite pixels differ from STD where the capture neither rounds nor clips"
    [ "$(json_field table.json "['capture_vs_rtt_differing_unexplained']")" = "0" ] || fail "unexplained atlas texels against RTT"
    # A saved frame replays to the same image.
    "$tessera" replay r/rtta_0003.tframe -o replay.png --stats replay.json > /dev/null
    want=$(python3 -c "import json; print([r for r in json.load(open('r/frames.json'))['frames'] if r['frame'] == 3 and r['mode'] == 'rtta'][0]['image_sha256'])")
    [ "$(json_field replay.json "['image_sha256']")" = "$want" ] || fail "the saved RTTA frame does not replay to its image"
    # --texturing tab: TAB's output batches in the capture, the same composites in fewer draws.
    "$tessera" rtta render five --mode rtta --texturing tab --frames 4 --size 96x72 --save-every 2 --border 2 -o t --quiet > tab.json
    [ "$(json_field tab.json "['modes']['rtta']['draw_calls_max']")" = "2.0" ] || fail "the TAB capture is not one draw (plus the composite)"
    for f in 0 1 2 3; do
      a=$(python3 -c "import json; print([r for r in json.load(open('r/frames.json'))['frames'] if r['frame'] == $f and r['mode'] == 'rtta'][0]['image_sha256'])")
      b=$(python3 -c "import json; print([r for r in json.load(open('t/frames.json'))['frames'] if r['frame'] == $f][0]['image_sha256'])")
      [ "$a" = "$b" ] || fail "frame $f: the TAB capture composites to another image than the bind capture"
    done
    # ghosted-ao (Fig. 3D): the border defaults to the kernel's radius; occlusion and edges darken the
    # important object, so its composite differs from ghosted's.
    "$tessera" rtta render five --mode rtta --composite ghosted-ao --important 2 --frames 1 --size 96x72 --save-every 1 -o ao --quiet > ao.json
    "$tessera" rtta render five --mode rtta --composite ghosted --important 2 --border 2 --frames 1 --size 96x72 --save-every 1 -o gh --quiet > /dev/null
    [ "$(json_field ao.json "['border']")" = "2" ] || fail "ghosted-ao did not default to a border of 2"
    for f in rtta_0000.png rtta_0000.tframe atlas_0000.tframe; do [ -s "ao/$f" ] || fail "ghosted-ao did not write $f"; done
    cmp -s ao/rtta_0000.png gh/rtta_0000.png && fail "ghosted-ao draws the same image as ghosted"
    "$tessera" rtta params "$src/data/railway.glb" --size 128x96 > params.json
    [ "$(python3 -c "import json; print(len(json.load(open('params.json'))['records']))")" = "33" ] || fail "railway: not 33 records"
    "$tessera" rtta render --help > help.txt
    for word in "--composite" "--objects" "--layers" "--texturing" "--atlas" "--border" "ghosted-ao"; do
      grep -qF -- "$word" help.txt || fail "rtta render --help does not explain $word"
    done
    ;;
  rtta_golden_command_reproduces_the_golden_frames)
    "$tessera" rtta render "$src/data/railway.glb" --mode rtta --path orbit --frames 24 --size 256x192 --save-every 8 -o r --quiet > /dev/null
    for f in 0 8 16 23; do
      want=$(json_field "$src/golden/manifest.json" "['tests']['rtta_railway.f$(printf %03d $f)']['image_sha256']")
      got=$(python3 -c "import json; print([r for r in json.load(open('r/frames.json'))['frames'] if r['frame'] == $f][0]['image_sha256'])")
      [ "$want" = "$got" ] || fail "frame $f: $got, golden $want"
    done
    ;;
  rtta_bad_input_exits_2)
    refused 2 "--border -1" "$tessera" rtta render five --border -1 -o o1
    refused 2 "--border 65" "$tessera" rtta render five --border 65 -o o1
    refused 2 "--atlas: atlas 128x128: must hold the viewport 128x128 plus a border of 1" "$tessera" rtta render five --size 128x128 --atlas 128x128 -o o1
    refused 2 "--mode 'nope'" "$tessera" rtta render five --mode nope -o o1
    refused 2 "--border 1: --composite ghosted-ao needs at least 2 (the occlusion kernel's radius)" \
      "$tessera" rtta render five --composite ghosted-ao --border 1 -o o1
    refused 2 "--texturing 'bound'" "$tessera" rtta render five --texturing bound -o o1
    refused 2 "--objects 'x'" "$tessera" rtta render five --objects x -o o1
    refused 2 "--layers 'lazy:0'" "$tessera" rtta render five --layers lazy:0 -o o1
    refused 2 "--important 5: the scene has 5 objects" "$tessera" rtta render five --important 5 -o o1
    refused 2 "nope.glb" "$tessera" rtta render nope.glb -o o1
    refused 2 "nope.glb" "$tessera" rtta params nope.glb
    printf 'not a path\n' > bad.path
    refused 2 "bad.path" "$tessera" rtta render five --path bad.path -o o2
    [ ! -e o1 ] || fail "a refused run left its output directory"
    ;;
  tab_bad_input_exits_2)
    refused 2 "--a-max: 9 must be in 1..8" "$tessera" tab build "$src/data/railway.glb" -o x.tab --a-max 9
    [ ! -e x.tab ] || fail "a refused build left x.tab"
    refused 2 "--b-max: 3 must be above 3" "$tessera" tab build "$src/data/railway.glb" -o x.tab --b-max 3
    refused 2 "--d-max: 0 must be in 1..2048" "$tessera" tab build "$src/data/railway.glb" -o x.tab --d-max 0
    refused 2 "nope.glb" "$tessera" tab build nope.glb -o x.tab
    "$tessera" tab build "$src/data/railway.glb" -o ok.tab --quiet > /dev/null
    head -c 1000 ok.tab > short.tab
    refused 2 "short.tab" "$tessera" tab info short.tab
    refused 2 "short.tab" "$tessera" tab render short.tab -o out
    cp ok.tab flipped.tab
    printf '\x55' | dd of=flipped.tab bs=1 seek=5000 conv=notrunc 2> /dev/null
    refused 2 "flipped.tab" "$tessera" tab info flipped.tab
    refused 2 "--baseline and --both" "$tessera" tab render ok.tab --baseline --both -o out2
    ls | grep -q 'tmp' && fail "a temporary file was left: $(ls)"
    ;;
  replay_matches_render)
    # 7 threads, more than CI's cores: the backend must really run them (oneTBB would cap them at the
    # cores and warn on stderr) and give the 1-thread bytes.
    "$tessera" render texture_array --threads 7 -o a.png --stats a.json --record a.tframe > /dev/null 2> render.err
    grep -q "TBB Warning" render.err && fail "oneTBB capped the threads: $(cat render.err)"
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
  image_module_missing_or_wrong_is_a_clear_error)
    # Image files go through libtessera_image_module.so, loaded at the first image write
    # (raster/image_module.h). A module that cannot be found or loaded is named, with the way out, and
    # the image that could not be written is not left behind, not even as a temporary.
    refused 2 "cannot find the image module libtessera_image_module.so" \
      env TESSERA_IMAGE_MODULE="$work/none/libx.so" "$tessera" render blend -o blend.png
    grep -qF "$work/none/libx.so: no such file" refused.err || fail "the path tried is not named: $(cat refused.err)"
    grep -qF "set TESSERA_IMAGE_MODULE" refused.err || fail "no way out named: $(cat refused.err)"
    echo "not a library" > fake.so
    refused 2 "cannot load the image module $work/fake.so" env TESSERA_IMAGE_MODULE="$work/fake.so" "$tessera" render blend -o blend.png
    [ -z "$(ls -A | grep -v -e '^refused\.' -e '^fake\.so$')" ] || fail "left behind: $(ls -A)"
    # A command that touches no image never loads it: the refusal of a bad size needs no module.
    refused 2 "--size '12y4'" env TESSERA_IMAGE_MODULE="$work/none/libx.so" "$tessera" render blend --size 12y4
    # And the module of the build is found without the variable.
    "$tessera" render blend -o blend.png > /dev/null || fail "render with the build's own module failed"
    [ -s blend.png ] || fail "no blend.png"
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
    [ "$(json_field info.json "['layers']")" = 1 ] || fail "a city without a light map has $(json_field info.json "['layers']") layers"
    # --light-map: the glTF occlusionTexture of every facade, the tree's layer 1, in the one file and the parts.
    "$tessera" city --preset berlin --buildings 6 --seed 3 --light-map -o lit --quiet > lit.json
    "$tessera" city --preset berlin --buildings 6 --seed 3 --light-map --split-per-building -o litsplit --quiet > /dev/null
    [ -s lit/lightmap.png ] && [ -s litsplit/lightmap.png ] || fail "no lightmap.png written"
    "$tessera" mta build lit/berlin.gltf -o lit.mta --d-min 50 --quiet > /dev/null
    "$tessera" mta build litsplit/berlin.json -o litsplit.mta --d-min 50 --quiet > /dev/null
    "$tessera" mta info lit.mta > litinfo.json 2> /dev/null
    [ "$(json_field litinfo.json "['layers']")" = 2 ] || fail "the light map is not layer 1: $(cat litinfo.json)"
    cmp -s lit.mta litsplit.mta || fail "the split city's light-mapped tree differs from the one-file city's"
    # The light map drawn (§5.1.3): with every block loaded the lit and the plain tree draw the same nodes;
    # the lit frames bind layer 1 on unit 1 (the plain ones never) and, where they differ, every channel is
    # darker (the light map multiplies by at most 1). compare lists the first differing pixels.
    "$tessera" mta render tree.mta --frames 4 --size 160x120 --save-every 1 --budget unlimited -o plainr --quiet > /dev/null
    "$tessera" mta render lit.mta --frames 4 --size 160x120 --save-every 1 --budget unlimited -o litr --quiet > /dev/null
    python3 -c "
import json, sys
lit, plain = (json.load(open(d + '/frames.json'))['frames'] for d in ('litr', 'plainr'))
for a, b in zip(lit, plain):
    for k in ('nodes_with_atlas', 'nodes_with_original_textures', 'leaves_drawn', 'draw_calls'):
        if a[k] != b[k]: sys.exit('frame %d: %s %d lit, %d plain' % (a['frame'], k, a[k], b[k]))
    if a['texture_binds_unit1'] < 1 or b['texture_binds_unit1'] != 0: sys.exit('frame %d: unit 1 binds' % a['frame'])
" || fail "the lit and the plain frames differ in what they draw or bind"
    darker=0
    for f in 0000 0001 0002 0003; do
      rc=0; "$tessera" compare litr/frame_$f.png plainr/frame_$f.png > cmp.json || rc=$?
      [ "$rc" = 2 ] || continue
      python3 -c "
import json, sys
d = json.load(open('cmp.json'))
for p in d['first_differences']:
    if any(l > q for l, q in zip(p['expected'][:3], p['actual'][:3])): sys.exit('pixel %d,%d: lit %s, plain %s' % (p['x'], p['y'], p['expected'], p['actual']))
" || fail "frame $f: a lit pixel is brighter than the plain one"
      darker=$((darker + 1))
    done
    [ "$darker" -ge 1 ] || fail "no lit frame differs from the plain one: the light map is not drawn"
    ;;
  scene_manifest_and_directory_work_in_every_model_command)
    # A berlin city written whole and split per building (docs/model-import.md "Scenes of several files"):
    # every command that takes a model takes the manifest (loadModel reads it), and the split city gives
    # the same atlas tree bytes, the same TAB and RTTA images and the same TAB batches as the one-file city.
    "$tessera" city --preset berlin --buildings 5 --texture-size 32 -o one --quiet > /dev/null
    "$tessera" city --preset berlin --buildings 5 --texture-size 32 -o split --split-per-building --load-back --quiet > split.json
    [ "$(json_field split.json "['gltf']")" = "split/berlin.json" ] || fail "the split city's summary does not name its manifest"
    [ "$(json_field split.json "['load_back']['triangles']")" = 104 ] || fail "the manifest loads with another triangle count"
    [ -s split/parts/building_4.gltf ] && [ -s split/parts/ground.gltf ] || fail "the parts were not written"
    "$tessera" mta build one/berlin.gltf -o one.mta --d-min 50 --quiet > /dev/null
    "$tessera" mta build split/berlin.json -o split.mta --d-min 50 --quiet > /dev/null
    cmp -s one.mta split.mta || fail "the atlas tree of the manifest differs from the one-file city's"
    "$tessera" mta runs split.mta --frames 2 --size 96x72 -o runs --quiet > runs.json
    "$tessera" texel split/berlin.json --frames 2 --size 96x72 --save-every 0 -o texel --quiet > texel.json
    [ -s texel/tree.mta ] || fail "texel did not build the manifest's tree"
    for v in one split; do
      scene=one/berlin.gltf; [ $v = split ] && scene=split/berlin.json
      "$tessera" tab build "$scene" -o $v.tab --quiet > tab_$v.json
      "$tessera" tab render $v.tab --both --frames 3 --size 96x72 --save-every 2 -o tab_$v --quiet > /dev/null
      "$tessera" rtta render "$scene" --objects node --frames 2 --size 96x72 --save-every 1 -o rtta_$v --quiet > rtta_$v.json
    done
    [ "$(json_field rtta_split.json "['object_count']")" = 6 ] || fail "RTTA does not see 5 buildings and the ground"
    for k in arrays geometry_batches input_batches output_batches triangles textures; do
      [ "$(json_field tab_one.json "['$k']")" = "$(json_field tab_split.json "['$k']")" ] || fail "TAB's $k differ"
    done
    n=0
    for f in tab_one/*_0*.png rtta_one/*_0*.png; do  # plot.png shows timings
      [ -e "$f" ] || continue
      cmp -s "$f" "${f/_one/_split}" || fail "$f differs between the one-file city and its manifest"
      n=$((n + 1))
    done
    [ $n -ge 14 ] || fail "only $n images compared"
    # A directory of model files: every part, identity transforms, the same triangles.
    "$tessera" tab build split/parts -o dir.tab --quiet > dir.json
    [ "$(json_field dir.json "['triangles']")" = 104 ] || fail "the directory does not give the 104 triangles"
    # Bad manifests exit 2 naming the manifest and the JSON pointer, in every command.
    printf '{"schema": 1, "models": [{"file": "split/parts/ground.gltf", "transform": [1, 0, 0]}]}' > bad.json
    refused 2 "bad.json: /models/0/transform: expected 16 numbers, got 3" "$tessera" mta build bad.json -o bad.mta --quiet
    refused 2 "bad.json: /models/0/transform: expected 16 numbers, got 3" "$tessera" tab build bad.json -o bad.tab --quiet
    refused 2 "bad.json: /models/0/transform: expected 16 numbers, got 3" "$tessera" rtta render bad.json -o bad --quiet
    refused 2 "bad.json: /models/0/transform: expected 16 numbers, got 3" "$tessera" texel bad.json -o bad --quiet
    printf '{"schema": 1,\n "models": [ oops ]}' > syntax.json
    refused 2 "syntax.json:2:14: not valid JSON" "$tessera" mta build syntax.json -o bad.mta --quiet
    printf '{"schema": 1, "models": [{"file": "split/berlin.json"}]}' > nested.json
    refused 2 "nested.json: /models/0/file: 'split/berlin.json' is a scene manifest" "$tessera" tab build nested.json -o bad.tab --quiet
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
    # --no-group-binds records the traversal's leaf-by-leaf order: the same nodes and triangles, and no
    # fewer binds (grouped, each texture is bound once; this city's textures all have their own images).
    "$tessera" mta render tree.mta --frames 40 --size 160x120 --capacity 8 --budget 2blocks --save-every 0 --no-group-binds \
      -o render2 --quiet > /dev/null
    python3 - render/frames.json render2/frames.json <<'PY' || fail "--no-group-binds does not draw what the grouped render draws"
import json, sys
g, u = [json.load(open(p)) for p in sys.argv[1:]]
assert g["options"]["draw_order"] == "grouped by texture", g["options"]
assert u["options"]["draw_order"] == "leaf by leaf (--no-group-binds)", u["options"]
for a, b in zip(g["frames"], u["frames"]):
    for k in ("triangles_drawn", "leaves_drawn", "nodes_with_atlas", "nodes_with_original_textures", "blocks_resident"):
        assert a[k] == b[k], (a["frame"], k, a[k], b[k])
    assert a["texture_binds"] <= b["texture_binds"], (a["frame"], a["texture_binds"], b["texture_binds"])
PY
    # --max-binds: the cap is met in every frame, the nodes it coarsened are counted, the rest is the same.
    cap=$(python3 -c "import json,sys; print(max(2, int(json.load(open(sys.argv[1]))['summary']['texture_binds_max']) - 2))" render/frames.json)
    "$tessera" mta render tree.mta --frames 40 --size 160x120 --capacity 8 --budget 2blocks --save-every 0 --max-binds "$cap" \
      -o render3 --quiet > /dev/null
    python3 - render/frames.json render3/frames.json "$cap" <<'PY' || fail "--max-binds $cap is not met or not counted"
import json, sys
g, c = (json.load(open(p)) for p in sys.argv[1:3])
cap = int(sys.argv[3])
assert c["options"]["max_binds"] == cap and g["options"]["max_binds"] == 0, c["options"]
s = c["summary"]
assert s["frames_with_nodes_coarsened_for_binds"] > 0 and 0 <= s["bind_cap_worst_ratio"] < 1, s  # 0: the eye inside the node's box
assert g["summary"]["bind_cap_worst_ratio"] is None, g["summary"]
for a, b in zip(g["frames"], c["frames"]):
    assert b["texture_binds"] <= cap or s["frames_over_max_binds"] > 0, (b["frame"], b["texture_binds"])
    if a["texture_binds"] <= cap:
        assert b["nodes_coarsened_for_binds"] == 0 and a["image_sha256"] == b["image_sha256"], b["frame"]
    assert b["triangles_drawn"] == a["triangles_drawn"], b["frame"]
PY
    if "$tessera" mta render tree.mta --max-binds 8 --no-group-binds -o render4 --quiet > /dev/null 2> cap.err; then
      fail "--max-binds with --no-group-binds accepted"
    fi
    grep -q -- "--no-group-binds" cap.err || fail "the refusal does not name --no-group-binds: $(cat cap.err)"
    "$tessera" texel tree.mta --frames 20 --size 160x120 --budget unlimited --capacity 512 --save-every 10 -o texel --quiet > texel.json
    [ "$(json_field texel.json "['magnification_violations_when_every_needed_block_resident']")" = "0" ] || fail "violations: $(cat texel.json)"
    for f in texel.json histogram.png texel_0000.png texel_0019.png texel_axis_0000.png; do [ -s "texel/$f" ] || fail "texel did not write $f"; done
    [ "$(json_field texel.json "['per_axis_magnification_violations_when_every_needed_block_resident']")" != "" ] || fail "no per-axis count"
    # The frustum's corner ray for every node instead of the per-node bound: never fewer nodes drawn.
    "$tessera" texel tree.mta --frames 20 --size 160x120 --budget unlimited --capacity 512 --save-every 0 --distance-bound corner -o texelc --quiet > texelc.json
    [ "$(json_field texelc.json "['magnification_violations_when_every_needed_block_resident']")" = "0" ] || fail "corner violations: $(cat texelc.json)"
    python3 - texel.json texelc.json <<'PY' || fail "the per-node bound drew more nodes than the corner ray"
import json, sys
n, c = (json.load(open(p)) for p in sys.argv[1:])
assert n["atlas_nodes_drawn"] + n["original_leaves_drawn"] <= c["atlas_nodes_drawn"] + c["original_leaves_drawn"], (n, c)
PY
    if "$tessera" texel tree.mta --distance-bound axis -o texelbad --quiet > /dev/null 2> bad.err; then fail "--distance-bound axis accepted"; fi
    grep -q -- "--distance-bound" bad.err || fail "bad --distance-bound not named: $(cat bad.err)"
    "$tessera" mta runs tree.mta --frames 12 --size 128x96 --save-every 0 -o runs --quiet > runs.json
    for m in original dummy atlas_tree; do
      [ "$(json_field runs.json "['$m']['draw_calls_max']")" != "" ] || fail "runs lacks $m"
    done
    [ -s runs/runs.png ] || fail "runs did not write runs.png"
    # Run 1 uploads every visible original: over --memory-budget it stops, naming the run, frame and option.
    if "$tessera" mta runs tree.mta --frames 2 --size 128x96 --save-every 0 --memory-budget 64KiB -o runs2 --quiet \
        > /dev/null 2> budget.err; then fail "a run over --memory-budget 64KiB passed"; fi
    grep -q "original run, frame 0" budget.err && grep -q -- "--memory-budget" budget.err \
      || fail "the budget error does not name the run and the option: $(cat budget.err)"
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
    # railway.glb at the default d_min plans 13.3 GiB: --max-output lets it start (it is stopped long before).
    "$tessera" mta build "$src/data/railway.glb" -o tree.mta --max-output 16GiB --quiet > /dev/null 2>&1 & pid=$!
    wait_for_temporary
    kill -TERM "$pid"
    rc=0; wait "$pid" || rc=$?
    [ "$rc" = 143 ] || fail "SIGTERM: exit status $rc, expected 143"
    ls tree.mta.tmp-* > /dev/null 2>&1 && fail "SIGTERM left a temporary: $(ls tree.mta.tmp-*)"
    [ "$(cat tree.mta)" = "previous output" ] || fail "SIGTERM damaged the previous output"
    # SIGKILL cannot be caught: the temporary stays until the next writer of tree.mta removes it.
    "$tessera" mta build "$src/data/railway.glb" -o tree.mta --max-output 16GiB --quiet > /dev/null 2>&1 & pid=$!
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
  parse_errors_exit_2)
    # What CLI11 refuses is bad input like any other (the README promises 2), with CLI11's message.
    refused 2 "The following argument was not expected: --bogus" "$tessera" render blend --bogus
    refused 2 "The following argument was not expected: extra" "$tessera" render blend extra
    refused 2 "--threads: 1 required" "$tessera" render blend --threads
    refused 2 "scene is required" "$tessera" render
    refused 2 "A subcommand is required" "$tessera"
    refused 2 "A subcommand is required" "$tessera" mta
    refused 2 "--buildings: Value 0 not in range 1 to 1000000" "$tessera" city --preset berlin --buildings 0 -o c
    refused 2 "Could not convert: --seed = abc" "$tessera" city --preset berlin --seed abc -o c
    refused 2 "--threads 'abc': not a whole number" "$tessera" render blend --threads abc
    refused 2 "SIMD target 'neon' is not available in this build on this CPU; available:" "$tessera" golden check --simd neon
    # Help is no error.
    "$tessera" --help > help.txt || fail "--help exits $?"
    "$tessera" mta render --help > help.txt || fail "mta render --help exits $?"
    [ ! -e c ] || fail "a refused command wrote its output directory"
    ;;
  output_in_the_way_exits_2)
    printf 'not a directory' > afile
    refused 2 "afile: exists and is not a directory (-o names the output directory)" \
      "$tessera" demo -o afile --no-gl --no-mta --no-tab --no-rtta --no-thread-check
    refused 2 "afile: exists and is not a directory" "$tessera" city --preset berlin --buildings 2 -o afile --quiet
    # The output directory is checked before the tree is opened (tree.mta does not even exist).
    refused 2 "afile/sub: cannot create the directory: afile is not a directory" \
      "$tessera" mta render tree.mta -o afile/sub --quiet
    refused 2 "afile/x/y: cannot create the directory: afile is not a directory" "$tessera" mta runs tree.mta -o afile/x/y
    refused 2 "afile: exists and is not a directory" "$tessera" texel tree.mta -o afile
    refused 2 "afile: exists and is not a directory (--report names the output directory)" \
      "$tessera" crosscheck blend --backends cpu,cpu --report afile
    "$tessera" render blend -o a.png > /dev/null
    refused 2 "afile/r: cannot create the directory: afile is not a directory (--report names" \
      "$tessera" compare a.png a.png --report afile/r
    # A file output where a directory is, or under a file.
    mkdir adir
    refused 2 "adir" "$tessera" render blend -o adir
    refused 2 "afile/x.png" "$tessera" render blend -o afile/x.png
    refused 2 "afile/s.json" "$tessera" render blend --stats afile/s.json
    # Unwritable places: /proc refuses new entries even to root; a read-only directory refuses others.
    refused 2 "/proc/tessera_cli_test: cannot create the directory" "$tessera" demo -o /proc/tessera_cli_test --no-gl --no-mta --no-tab --no-rtta
    if [ "$(id -u)" != 0 ]; then
      mkdir ro && chmod 555 ro
      refused 2 "ro/out: cannot create the directory: Permission denied" "$tessera" demo -o ro/out --no-gl --no-mta --no-tab --no-rtta
      refused 2 "ro: cannot write into it" "$tessera" demo -o ro --no-gl --no-mta --no-tab --no-rtta
      chmod 755 ro
    fi
    [ "$(cat afile)" = "not a directory" ] || fail "afile was changed"
    ;;
  threads_above_the_bound_exit_2)
    # One bound, kMaxThreads = 256 (docs/limits.md), for every --threads; checked before any work, so the
    # missing inputs below are never opened.
    for cmd in "render blend" "replay none.tframe" "demo -o d --no-gl --no-mta --no-tab --no-rtta" "crosscheck blend" "visibility city_ids" \
               "bench crosscheck blend" "mta build none.glb -o t.mta" "mta render none.mta -o r" "mta runs none.mta -o r" \
               "texel none.mta -o r"; do
      for n in 257 100000; do
        # shellcheck disable=SC2086
        refused 2 "--threads '$n': more than the limit of 256 worker threads" "$tessera" $cmd --threads $n
      done
    done
    refused 2 "--threads '4294967297': more than the limit of 256" "$tessera" mta build none.glb -o t.mta --threads 4294967297
    refused 2 "--threads '-1': not a whole number (0..256" "$tessera" mta render none.mta -o r --threads -1
    [ ! -e d ] && [ ! -e r ] || fail "a refused command wrote its output directory"
    "$tessera" render blend --threads 0 > /dev/null || fail "--threads 0 (all cores) refused"
    "$tessera" render blend --threads 3 --size 32x16 > s.json || fail "--threads 3 refused"
    [ "$(json_field s.json "['threads']")" = 3 ] || fail "threads: $(json_field s.json "['threads']")"
    "$tessera" render --help | grep -qF -- "(0..256, 0 = all cores)" || fail "render --help does not give the range"
    ;;
  size_that_wraps_exits_2)
    # 4294967297 = 2^32 + 1 used to wrap around to 1 and render 1x1.
    for size in 4294967297x1 1x4294967297 18446744073709551617x1 16385x1 1x16385 0x5 5x0 -1x5 12x 640x480x2 '+5x5'; do
      refused 2 "--size '$size'" "$tessera" render blend --size "$size"
    done
    refused 2 "the width 4294967297 is outside 1..16384" "$tessera" render blend --size 4294967297x1
    refused 2 "the height 16385 is outside 1..16384" "$tessera" render blend --size 1x16385
    # The same parser behind every --size, checked before the input is opened.
    refused 2 "--size '4294967297x1'" "$tessera" crosscheck blend --backends cpu,cpu --size 4294967297x1
    refused 2 "--size '4294967297x1'" "$tessera" visibility city_ids --size 4294967297x1
    refused 2 "--size '4294967297x1'" "$tessera" bench crosscheck blend --size 4294967297x1
    refused 2 "--size '4294967297x1'" "$tessera" mta render none.mta --size 4294967297x1 -o r
    refused 2 "--size '4294967297x1'" "$tessera" texel none.mta --size 4294967297x1 -o r
    "$tessera" render blend --size 16384x1 > s.json || fail "16384x1 refused"
    "$tessera" render blend --size 7X3 > s.json || fail "7X3 refused"
    [ "$(json_field s.json "['images'][0]['width']")x$(json_field s.json "['images'][0]['height']")" = 7x3 ] \
      || fail "7X3 rendered $(json_field s.json "['images'][0]['width']")x$(json_field s.json "['images'][0]['height']")"
    ;;
  tau_nan_or_zero_exits_2)
    # Every real-valued option is finite and inside its documented range; NaN compares false with
    # everything, so a check written as "x < 0" let it through.
    for tau in nan NaN 0 -1 inf -inf 1e999 0x1p3 '' 1.5x; do
      refused 2 "--tau '$tau': expected a finite number > 0" "$tessera" mta build none.glb -o t.mta --tau "$tau"
    done
    for tau in nan 0; do
      refused 2 "--tau '$tau': expected a finite number > 0" "$tessera" mta render none.mta -o r --tau "$tau"
      refused 2 "--tau '$tau': expected a finite number > 0" "$tessera" texel none.mta -o r --tau "$tau"
    done
    refused 2 "--d-min '-1': expected a finite number >= 0" "$tessera" mta build none.glb -o t.mta --d-min -1
    refused 2 "--d-min 'nan'" "$tessera" texel none.mta -o r --d-min nan
    refused 2 "--d-min-divisor '0': expected a finite number > 0" "$tessera" mta build none.glb -o t.mta --d-min-divisor 0
    refused 2 "--fov '180': expected a finite number in (0, 180)" "$tessera" mta build none.glb -o t.mta --fov 180
    refused 2 "--tan-half-fov 'inf'" "$tessera" mta build none.glb -o t.mta --tan-half-fov inf
    refused 2 "--critical-threshold '1.5': expected a finite number in [0, 1]" \
      "$tessera" mta build none.glb -o t.mta --critical-threshold 1.5
    refused 2 "--memory-limit 'inf'" "$tessera" mta build none.glb -o t.mta --memory-limit inf
    refused 2 "--capacity 'nan': expected a finite number in (0, 1000000000]" "$tessera" mta render none.mta -o r --capacity nan
    refused 2 "--capacity '0'" "$tessera" mta runs none.mta -o r --capacity 0
    "$tessera" render blend -o a.png > /dev/null
    refused 2 "--fail 'nan': expected a finite number >= 0" "$tessera" compare a.png a.png --fail nan
    refused 2 "--warn '-1'" "$tessera" compare a.png a.png --warn -1
    refused 2 "--failpercent '101': expected a finite number in [0, 100]" "$tessera" compare a.png a.png --failpercent 101
    refused 2 "--warnpercent 'nan'" "$tessera" compare a.png a.png --warnpercent nan
    "$tessera" compare a.png a.png --fail 0.5 --failpercent 100 > /dev/null || fail "valid thresholds refused"
    "$tessera" mta build --help | grep -qF "(a finite number > 0)" || fail "mta build --help does not give --tau's range"
    [ ! -e t.mta ] && [ ! -e r ] || fail "a refused command wrote its output"
    ;;
  frame_over_the_memory_budget_exits_2)
    # The fuzz campaign's frame, encoded by hand (docs/tframe-format.md): a layered 16384 x 16384 x 2048
    # RGBA32F render target, cleared. 16 bytes * 16384^2 * 2048 = 2^43 bytes = 8 TiB; it used to pass
    # validation and die in bad_alloc (exit 3).
    python3 - big.tframe <<'PY'
import hashlib, struct, sys
def command(opcode, payload): return struct.pack('<HI', opcode, len(payload)) + payload
body = (command(0, struct.pack('<IBBIIIII', 1, 1, 3, 16384, 16384, 2048, 1, 0))  # CreateTexture 1: Tex2DArray RGBA32F
        + command(18, struct.pack('<7I', 1, 0, 0, 0, 0, 0, 0xffffffff))          # SetRenderTarget color[0] = 1, layered
        + command(19, struct.pack('<5I', 0, 0, 0, 0, 0x3f800000)))               # ClearColor 0 to (0, 0, 0, 1)
header = b'TSFRAME\0' + struct.pack('<IIQQQ', 1, 72, 3, 0, 2) + hashlib.sha256(body).digest()
open(sys.argv[1], 'wb').write(header + body)
PY
    message="command 0 (CreateTexture): frame: needs 8.0 TiB of textures, buffers and render targets, over the limit of 4.0 GiB by 8.0 TiB (raise it with --memory-budget)"
    refused 2 "big.tframe: 1 problem in the command list" "$tessera" replay big.tframe -o big.png
    refused 2 "$message" "$tessera" replay big.tframe -o big.png
    refused 2 "$message" "$tessera" crosscheck big.tframe --backends cpu,cpu
    refused 2 "big.tframe: 1 problem" "$tessera" visibility big.tframe
    refused 2 "$message" "$tessera" bench crosscheck big.tframe
    [ ! -e big.png ] || fail "replay wrote an image"
    # `validate` lists it (exit 1: it found a problem) ...
    rc=0; "$tessera" validate big.tframe > v.txt || rc=$?
    [ "$rc" = 1 ] || fail "validate: exit status $rc"
    grep -qF "big.tframe: $message" v.txt || fail "validate: $(cat v.txt)"
    # ... and it is the only problem: with a budget of 8 TiB the frame is valid.
    "$tessera" validate big.tframe --memory-budget 8TiB > v.txt || fail "8 TiB budget: $(cat v.txt)"
    grep -qF "big.tframe: 3 commands, 0 problems" v.txt || fail "validate: $(cat v.txt)"
    # The budget works both ways on a real frame: blend's 256x128 RGBA8 target alone is 128 KiB.
    "$tessera" render blend --record blend.tframe > /dev/null
    refused 2 "over the limit of 127.0 KiB by" "$tessera" replay blend.tframe --memory-budget 127KiB
    "$tessera" replay blend.tframe --memory-budget 1MiB > /dev/null || fail "a 1 MiB budget refused blend"
    refused 2 "--memory-budget '4GB': unknown unit 'GB'" "$tessera" replay blend.tframe --memory-budget 4GB
    refused 2 "--memory-budget '0': a frame budget must be at least 1 byte" "$tessera" render blend --memory-budget 0
    refused 2 "--memory-budget '16777216TiB': more than 2^64 - 1 bytes" "$tessera" validate blend.tframe --memory-budget 16777216TiB
    ;;
  atlas_tree_build_refuses_a_run_away_tree_and_fits_one)
    # Issue 14 §2. railway.glb at the default d_min plans 17,395 nodes (2.8 GiB of S3TC chains; 12.8 GiB raw
    # with --raw; 18,168 nodes and 13.3 GiB raw before the packing turned wide areas): over --max-output the
    # build stops before the output exists, naming the size, the nodes and a d_min that fits.
    # Under TESSERA_CLI_SANITIZED the limit is 10 MiB (d_min 9, 37 nodes, instead of 2.5 and 541): the two
    # builds that fit it take 3.3 s instead of 8.7 s in Release, and the case under ASan 29 s instead of
    # 72 s. The refusals and the checks are the same; the sanitizers see railway.glb built and rendered by
    # railway_golden_command_reproduces_the_golden_frames too.
    limit=100MiB shown="100.0 MiB"
    if [ "${TESSERA_CLI_SANITIZED:-0}" = 1 ]; then limit=10MiB shown="10.0 MiB"; fi
    refused 2 "mta build: the tree would take 12.8 GiB (17,395 nodes" \
      "$tessera" mta build "$src/data/railway.glb" -o tree.mta --max-output $limit --quiet --raw
    refused 2 "mta build: the tree would take 2.8 GiB (17,395 nodes" \
      "$tessera" mta build "$src/data/railway.glb" -o tree.mta --max-output $limit --quiet
    for part in "but --max-output is $shown" "fits (" ", or --fit $limit, or raise --max-output"; do
      grep -qF -- "$part" refused.err || fail "the refusal lacks '$part': $(cat refused.err)"
    done
    [ -z "$(ls -A | grep -v '^refused\.')" ] || fail "a refused build left files behind: $(ls -A)"
    d=$(sed -n 's/.*pass --d-min \([0-9.e+-]*\),.*/\1/p' refused.err)
    [ -n "$d" ] || fail "no d_min suggested: $(cat refused.err)"
    # The suggestion builds within the limit, and the plan's estimate is the file's size to the byte.
    "$tessera" mta build "$src/data/railway.glb" -o tree.mta --d-min "$d" --max-output $limit --quiet > build.json
    size=$(stat -c %s tree.mta)
    [ "$size" -le $(( ${limit%MiB} * 1024 * 1024 )) ] || fail "the suggested d_min $d wrote $size bytes"
    [ "$(json_field build.json "['build']['estimated_bytes']")" = "$size" ] || fail "estimate != file size $size"
    # --fit searches the same grid from the same start: it chooses the suggested d_min.
    "$tessera" mta build "$src/data/railway.glb" -o fit.mta --fit $limit --quiet > fit.json
    [ "$(json_field fit.json "['build']['fit']['d_min'] == $d")" = True ] || fail "--fit chose $(json_field fit.json "['build']['fit']")"
    cmp -s tree.mta fit.mta || fail "--fit's tree differs from the one built with --d-min $d"
    refused 2 "--fit chooses d_min itself" "$tessera" mta build "$src/data/railway.glb" -o x.mta --fit 1GiB --d-min 3
    refused 2 "--max-output 'lots': not a byte size" "$tessera" mta build "$src/data/railway.glb" -o x.mta --max-output lots
    refused 2 "--max-output '8GB': " "$tessera" mta build "$src/data/railway.glb" -o x.mta --max-output 8GB
    refused 2 "--fit '0': must be at least 1 byte" "$tessera" mta build "$src/data/railway.glb" -o x.mta --fit 0
    refused 2 "--fit '-1MiB'" "$tessera" mta build "$src/data/railway.glb" -o x.mta --fit -1MiB
    [ ! -e x.mta ] || fail "a refused build wrote x.mta"
    "$tessera" mta build --help | grep -qF -- "--max-output" || fail "mta build --help does not explain --max-output"
    ;;
  model_over_its_budget_exits_2)
    # railway.glb has 26,797 triangles: a budget of 1,000 refuses it before any geometry is read.
    refused 2 "needs 26797 triangles" "$tessera" mta build "$src/data/railway.glb" -o tree.mta --model-budget-triangles 1000 --quiet
    grep -qF -- "--model-budget-triangles" refused.err || fail "the message does not name the option: $(cat refused.err)"
    [ ! -e tree.mta ] || fail "a refused build wrote tree.mta"
    refused 2 "--model-budget-textures" "$tessera" mta build "$src/data/railway.glb" -o tree.mta --model-budget-textures 1KiB --quiet
    refused 2 "--model-budget-instances" "$tessera" mta build "$src/data/railway.glb" -o tree.mta --model-budget-instances 0
    ;;
  mutants_table_names_the_killing_scene)
    # array_layers samples layers 0.7, 1.8 and 2.7, where floor(r) and floor(r + 1/2) differ: layer_floor
    # must be killed there, and the unmodified backend must raise no alarm (docs/mutants.md).
    "$tessera" mutants --strict --scenes array_layers,provoking_vertex --mutants layer_floor --report rep > m.json 2> m.err \
      || fail "mutants failed: $(cat m.err)"
    [ "$(json_field m.json "['mutants'][0]['killed_by']")" = "['array_layers']" ] || fail "layer_floor: $(cat m.json)"
    [ "$(json_field m.json "['false_alarms']['array_layers']")" = 0 ] || fail "a false alarm: $(cat m.json)"
    for f in report.json index.html; do [ -s "rep/$f" ] || fail "no rep/$f"; done
    grep -q "layer_floor" m.err || fail "no progress on stderr"
    refused 2 "unknown mutant 'nope'" "$tessera" mutants --mutants nope
    ;;
  texel_on_a_recorded_frame_and_its_comparison)
    # Any .tframe: per-pixel lambda from the oracle's sampler; a frame compared with itself agrees everywhere,
    # two different scenes of one size do not (exit 1), and the outputs of both modes are written.
    "$tessera" render mip_tunnel --record tunnel.tframe -o tunnel.png > /dev/null
    "$tessera" render texture_array --record array.tframe -o array.png > /dev/null
    "$tessera" texel tunnel.tframe -o one --threads 2 > one.json
    for f in texel.json lambda.png histogram.png lambda.i32; do [ -s "one/$f" ] || fail "texel did not write $f"; done
    [ "$(json_field one/texel.json "['frames'][0]['pixels_with_lookup']")" -gt 10000 ] || fail "no lookups: $(cat one.json)"
    [ "$(stat -c %s one/lambda.i32)" = $((256 * 256 * 4)) ] || fail "lambda.i32 is not 4 bytes per pixel"
    "$tessera" texel tunnel.tframe --against tunnel.tframe -o self > self.json
    [ "$(json_field self.json "['pixels_differing']")" = 0 ] || fail "a frame differs from itself: $(cat self.json)"
    [ "$(json_field self.json "['identical_lambda']")" = True ] || fail "self comparison: $(cat self.json)"
    [ -s self/lod_diff.png ] && [ -s self/lambda_against.png ] || fail "no difference map"
    rc=0; "$tessera" texel tunnel.tframe --against array.tframe -o other > other.json || rc=$?
    [ "$rc" = 1 ] || fail "different frames: exit status $rc, expected 1"
    [ "$(json_field other.json "['pixels_differing']")" -gt 0 ] || fail "no differences: $(cat other.json)"
    "$tessera" texel --help > help.txt
    grep -q -- "--against" help.txt && grep -q "lambda.i32" help.txt || fail "--help does not explain --against"
    ;;
  texel_on_a_bad_frame_exits_2)
    "$tessera" render mip_tunnel --record tunnel.tframe -o tunnel.png > /dev/null
    "$tessera" render lod_levels --record small.tframe -o small.png > /dev/null
    refused 2 "missing.tframe: not a readable file" "$tessera" texel missing.tframe -o r
    head -c 200 tunnel.tframe > cut.tframe
    refused 2 "cut.tframe" "$tessera" texel cut.tframe -o r
    refused 2 "tunnel.tframe is 256x256 but small.tframe is 128x64" "$tessera" texel tunnel.tframe --against small.tframe -o r
    refused 2 "only a .tframe input can be compared" "$tessera" texel tree.mta --against small.tframe -o r
    [ ! -e r ] || fail "bad input left an output directory behind"
    ;;
  bench_sweep_quick_writes_json_plot_and_page)
    # Structure only: no time is asserted (docs/bench.md), only that every point, fit and stage row is there.
    "$tessera" bench sweep --help | grep -qF -- "--quick" || fail "bench sweep --help lacks --quick"
    "$tessera" bench sweep --quick -o sweep > stdout.txt 2> progress.txt
    grep -qF "bench sweep: [1 thread, llvmpipe_strict] 4/4 tiny_tris 10000 tris" progress.txt \
      || fail "no progress on stderr: $(cat progress.txt)"
    for f in sweep.json sweep.png index.html; do [ -s "sweep/$f" ] || fail "bench sweep did not write $f"; done
    [ "$(head -c 4 sweep/sweep.png | tail -c 3)" = "PNG" ] || fail "sweep.png is not a PNG"
    python3 - sweep/sweep.json <<'PY' || fail "sweep.json has the wrong structure"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["quick"] is True and d["threads"] == [1] and d["repeat"] == 3
pts = d["points"]
# 2 fill_layers sizes + 2 triangle counts, 1 thread, 3 renderers, in plan order then renderer order.
assert len(pts) == 12, len(pts)
want = [("fill_layers", 320, 240, None), ("fill_layers", 640, 480, None), ("tiny_tris", 1280, 720, 1000),
        ("tiny_tris", 1280, 720, 10000)]
for i, p in enumerate(pts):
    wl, w, h, tris = want[i // 3]
    assert (p["workload"], p["width"], p["height"], p.get("triangles")) == (wl, w, h, tris), p
    assert p["renderer"] == ["oracle", "llvmpipe", "llvmpipe_strict"][i % 3], p
    assert p["threads"] == 1 and p["pixels"] == w * h and len(p["runs_ms"]) == 3
    assert p["p10_ms"] <= p["median_ms"] <= p["p90_ms"], p  # quantiles of the same runs, in order
    for k in ("median_ms", "p10_ms", "p90_ms", "cpu_ms"):
        assert isinstance(p[k], (int, float)) and p[k] >= 0, (k, p)
    assert ("ratio" in p) == (p["renderer"] != "oracle"), p
fits = d["fits"]
assert [(f["workload"], f["renderer"]) for f in fits] == [
    ("fill_layers", "oracle"), ("fill_layers", "llvmpipe"), ("fill_layers", "llvmpipe_strict"),
    ("tiny_tris", "oracle"), ("tiny_tris", "llvmpipe"), ("tiny_tris", "llvmpipe_strict")], fits
for f in fits:
    key = "ns_per_triangle" if f["workload"] == "tiny_tris" else "ns_per_pixel"
    assert key in f and f["points"] == 2 and "intercept_ms" in f, f
stages = d["stages"]
assert len(stages) == 4, stages
for s in stages:
    for k in ("frame_ms", "vertex_ms", "clip_ms", "setup_ms", "bin_ms", "rast_ms", "shade_ms", "sample_ms", "fragops_ms"):
        assert s[k] >= 0, (k, s)
assert "llvmpipe" in json.dumps(d["gl_info"]).lower()
PY
    grep -qF "Oracle stage times" sweep/index.html || fail "index.html lacks the stage table"
    grep -qF 'src="sweep.png"' sweep/index.html || fail "index.html does not show the plot"
    # A directory that is not empty is refused before any work, and stays as it was.
    refused 2 "not empty" "$tessera" bench sweep --quick -o sweep
    [ "$(ls sweep | wc -l)" = 3 ] || fail "the refused run changed the directory"
    ;;
  *) fail "unknown case $case_name" ;;
esac
echo "ok: $case_name"
