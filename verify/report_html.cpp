#include "verify/report_html.h"

#include <cstring>
#include <sstream>

#include "verify/html_escape.h"
#include "verify/image_read.h"

namespace tessera::verify {

namespace {

// JSON inside <script>: "</" would end the script element early.
std::string scriptSafe(const std::string& json) {
  std::string o;
  for (size_t i = 0; i < json.size(); ++i) {
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/')
      o += "<\\", ++i, o += '/';
    else
      o += json[i];
  }
  return o;
}

std::string base64(const uint8_t* p, size_t n) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string o;
  o.reserve((n + 2) / 3 * 4);
  for (size_t i = 0; i < n; i += 3) {
    const uint32_t v = uint32_t(p[i]) << 16 | (i + 1 < n ? uint32_t(p[i + 1]) << 8 : 0) | (i + 2 < n ? p[i + 2] : 0);
    o += kAlphabet[v >> 18 & 63];
    o += kAlphabet[v >> 12 & 63];
    o += i + 1 < n ? kAlphabet[v >> 6 & 63] : '=';
    o += i + 2 < n ? kAlphabet[v & 63] : '=';
  }
  return o;
}

// The stored pixel values as a typed-array payload for the inspector (null when too large). One JS
// typed array per image: the stored type when every channel shares it (half widened to float32),
// float64 for files that mix channel types.
nlohmann::json embedPixels(const DecodedImage& img) {
  if (img.bytes.size() > kMaxEmbeddedImageBytes) return nullptr;
  const ChannelType t = img.types.empty() ? ChannelType::UInt8 : img.types[0];
  bool uniform = true;
  for (ChannelType c : img.types) uniform = uniform && c == t;
  static const char* kNames[] = {"u8", "i8", "u16", "i16", "u32", "i32", "f32", "f32", "f64"};
  if (uniform && t != ChannelType::Half)
    return {{"type", kNames[int(t)]}, {"data", base64(img.bytes.data(), img.bytes.size())}};
  const bool asFloat = uniform;  // half -> float32 is exact
  std::vector<uint8_t> out(img.pixels() * size_t(img.channels()) * (asFloat ? 4 : 8));
  size_t k = 0;
  for (size_t p = 0; p < img.pixels(); ++p)
    for (int c = 0; c < img.channels(); ++c, ++k) {
      const double v = img.value(p, c);
      if (asFloat) {
        const float f = float(v);
        std::memcpy(out.data() + 4 * k, &f, 4);
      } else {
        std::memcpy(out.data() + 8 * k, &v, 8);
      }
    }
  return {{"type", asFloat ? "f32" : "f64"}, {"data", base64(out.data(), out.size())}};
}

std::string cell(const nlohmann::json& v) { return escapeHtml(v.is_string() ? v.get<std::string>() : v.dump()); }

void row(std::ostringstream& o, std::string_view name, const std::string& value) {
  o << "<tr><th>" << escapeHtml(name) << "</th><td>" << value << "</td></tr>\n";
}

constexpr const char* kStyle = R"(
body{font:14px/1.4 system-ui,sans-serif;margin:1.5em;background:#fafafa;color:#222}
h1{font-size:1.3em} h1 .pass{color:#1a7f37} h1 .warn{color:#9a6700} h1 .fail,h1 .mismatch,h1 .io_error{color:#cf222e}
table{border-collapse:collapse;margin:.5em 0} th,td{border:1px solid #ccc;padding:2px 8px;text-align:left;font-variant-numeric:tabular-nums}
th{background:#eee;font-weight:600}
.views{display:flex;flex-wrap:wrap;gap:12px;align-items:flex-start}
figure{margin:0} figcaption{font-weight:600;margin-bottom:4px}
canvas.view{image-rendering:pixelated;border:1px solid #888;cursor:crosshair;background:#444}
#inspector{font-family:ui-monospace,monospace;margin:.8em 0;min-height:5em}
.controls{margin:.6em 0} .controls>*{margin-right:1em}
)";

constexpr const char* kScript = R"(
(function(){
const W=META.w,H=META.h;
function decode(e){if(!e)return null;const s=atob(e.data);const u=new Uint8Array(s.length);
 for(let i=0;i<s.length;i++)u[i]=s.charCodeAt(i);
 const T={u8:Uint8Array,i8:Int8Array,u16:Uint16Array,i16:Int16Array,u32:Uint32Array,i32:Int32Array,f32:Float32Array,f64:Float64Array}[e.type];
 return new T(u.buffer);}
const PA=decode(PIXELS.a),PB=decode(PIXELS.b),NC=META.channels.length;
const names=['expected.png','actual.png','heatmap.png'],img={};let loaded=0;
let zoom=Math.max(1,Math.min(16,Math.floor(420/Math.max(W,H)))),showB=false,pin=null,cur=null,timer=null;
const zsel=document.getElementById('zoom');
for(const z of [1,2,3,4,6,8,12,16]){const o=document.createElement('option');o.value=z;o.textContent=z+'x';if(z===zoom)o.selected=true;zsel.appendChild(o);}
zsel.onchange=()=>{zoom=+zsel.value;draw();};
function put(id,im,sy){const c=document.getElementById(id);c.width=W*zoom;c.height=H*zoom;const x=c.getContext('2d');
 x.imageSmoothingEnabled=false;x.drawImage(im,0,sy||0,W,H,0,0,W*zoom,H*zoom);
 const p=pin||cur;if(p){x.strokeStyle='#0f0';x.lineWidth=1;x.strokeRect(p.x*zoom-1.5,p.y*zoom-1.5,zoom+3,zoom+3);}}
function draw(){if(loaded<3)return;put('cA',img['expected.png']);put('cB',img['actual.png']);put('cH',img['heatmap.png']);
 put('cX',showB?img['actual.png']:img['expected.png']);
 document.getElementById('altcap').textContent='alternate: '+(showB?'actual (B)':'expected (A)');
 const hm=img['heatmap.png'],lg=document.getElementById('legend');lg.width=hm.width;lg.height=hm.height-H;
 lg.getContext('2d').drawImage(hm,0,H,hm.width,hm.height-H,0,0,hm.width,hm.height-H);}
for(const n of names){const i=new Image();i.onload=()=>{loaded++;draw();};i.src=n;img[n]=i;}
document.getElementById('flip').onclick=()=>{showB=!showB;draw();};
document.getElementById('auto').onchange=e=>{clearInterval(timer);timer=e.target.checked?setInterval(()=>{showB=!showB;draw();},500):null;};
const alt=document.getElementById('cX');alt.onmouseenter=()=>{if(!timer){showB=true;draw();}};alt.onmouseleave=()=>{if(!timer){showB=false;draw();}};
function fmt(v){if(v===undefined)return '';if(Number.isNaN(v))return 'NaN';if(Number.isInteger(v))return String(v);return v.toPrecision(9);}
function diff(a,b){const na=Number.isNaN(a),nb=Number.isNaN(b);if(na||nb)return na&&nb?0:Infinity;if(a===b)return 0;return Math.abs(a-b);}
function inspect(p){const el=document.getElementById('inspector');if(!p){el.textContent='hover or click a pixel (click pins it)';return;}
 let h='<b>x '+(p.x+META.ox)+', y '+(p.y+META.oy)+'</b>'+(pin?' (pinned: click to release)':'');
 if(!PA||!PB){el.innerHTML=h+'<br>pixel values are not embedded (image larger than the embedding limit); see report.json';return;}
 h+='<table><tr><th>channel</th><th>expected</th><th>actual</th><th>|&Delta;|</th></tr>';
 const base=(p.y*W+p.x)*NC;for(let c=0;c<NC;c++){const a=PA[base+c],b=PB[base+c];
  h+='<tr><td>'+META.channels[c]+'</td><td>'+fmt(a)+'</td><td>'+fmt(b)+'</td><td>'+fmt(diff(a,b))+'</td></tr>';}
 el.innerHTML=h+'</table>';}
for(const id of ['cA','cB','cH','cX']){const c=document.getElementById(id);
 const at=e=>({x:Math.min(W-1,Math.max(0,Math.floor(e.offsetX/zoom))),y:Math.min(H-1,Math.max(0,Math.floor(e.offsetY/zoom)))});
 c.onmousemove=e=>{if(pin)return;cur=at(e);inspect(cur);draw();};
 c.onclick=e=>{pin=pin?null:at(e);cur=pin;inspect(pin);draw();};}
inspect(null);
})();
)";

}  // namespace

std::string renderReportHtml(const CompareResult& r, const nlohmann::json& report) {
  std::ostringstream o;
  const std::string status = compareStatusName(r.status);
  o << "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>tessera compare: " << status
    << "</title>\n<style>" << kStyle << "</style></head><body>\n";
  o << "<h1><span class=\"" << status << "\">" << escapeHtml(r.message) << "</span></h1>\n";
  o << "<table class=\"summary\">\n";
  row(o, "status", std::to_string(int(r.status)) + " (" + status + ")");
  row(o, "expected (A)", escapeHtml(r.pathA));
  row(o, "actual (B)", escapeHtml(r.pathB));
  row(o, "thresholds",
      "fail " + cell(report["options"]["fail"]) + " over " + cell(report["options"]["failpercent"]) +
          "% of pixels; warn " + cell(report["options"]["warn"]) + " over " + cell(report["options"]["warnpercent"]) +
          "%");
  if (r.images) {
    row(o, "size", std::to_string(r.width) + " x " + std::to_string(r.height));
    std::string channels, maxes, means;
    for (const auto& c : report["channels"]) {
      const std::string name = escapeHtml(c["name"].get<std::string>());
      channels += name + ": " + cell(c["type"]) + " (" + cell(c["units"]) + ") ";
      maxes += name + " " + cell(c["max_abs_diff"]) + " &nbsp; ";
      means += name + " " + cell(c["mean_abs_diff"]) + " &nbsp; ";
    }
    row(o, "channels", channels);
    row(o, "pixels", cell(report["pixels"]));
    row(o, "differing pixels", cell(report["differing_pixels"]));
    row(o, "exact match", cell(report["exact_match_percent"]) + " %");
    row(o, "failing / warning pixels", cell(report["failing_pixels"]) + " / " + cell(report["warning_pixels"]));
    row(o, "non-finite mismatches", cell(report["nonfinite_mismatches"]));
    row(o, "max |&Delta;| per channel", maxes);
    row(o, "mean |&Delta;| per channel", means);
    if (report.contains("max_abs_diff_at"))
      row(o, "largest |&Delta;| at",
          "x " + cell(report["max_abs_diff_at"]["x"]) + ", y " + cell(report["max_abs_diff_at"]["y"]) + ", channel " +
              cell(report["max_abs_diff_at"]["channel"]));
    row(o, "PSNR (dB)", cell(report["psnr"]));
  }
  o << "</table>\n";

  if (r.images) {
    o << "<div class=\"controls\"><label>zoom <select id=\"zoom\"></select></label>"
         "<button id=\"flip\">flip alternate view</button>"
         "<label><input type=\"checkbox\" id=\"auto\"> auto-flip</label>"
         "<span>hover the alternate view to see the actual image</span></div>\n";
    o << "<div class=\"views\">\n"
         "<figure><figcaption>expected (A)</figcaption><canvas class=\"view\" id=\"cA\"></canvas></figure>\n"
         "<figure><figcaption>actual (B)</figcaption><canvas class=\"view\" id=\"cB\"></canvas></figure>\n"
         "<figure><figcaption>|&Delta;| heat map</figcaption><canvas class=\"view\" id=\"cH\"></canvas><br>"
         "<canvas id=\"legend\"></canvas></figure>\n"
         "<figure><figcaption id=\"altcap\">alternate</figcaption><canvas class=\"view\" id=\"cX\"></canvas></figure>\n"
         "</div>\n<div id=\"inspector\"></div>\n";
    o << "<h2>Error histogram</h2>\n<p>Pixels by the largest channel |&Delta;| (" << cell(report["histogram"]["units"])
      << "), log scale.</p>\n<img src=\"histogram.png\" alt=\"error histogram\">\n<table><tr><th>|&Delta;|</th>";
    for (const auto& l : report["histogram"]["labels"]) o << "<th>" << cell(l) << "</th>";
    o << "</tr><tr><td>pixels</td>";
    for (const auto& c : report["histogram"]["counts"]) o << "<td>" << cell(c) << "</td>";
    o << "</tr></table>\n";
    o << "<h2>First differing pixels</h2>\n<table><tr><th>x</th><th>y</th><th>expected</th><th>actual</th></tr>\n";
    for (const auto& d : report["first_differences"])
      o << "<tr><td>" << cell(d["x"]) << "</td><td>" << cell(d["y"]) << "</td><td>" << cell(d["expected"])
        << "</td><td>" << cell(d["actual"]) << "</td></tr>\n";
    o << "</table>\n";
    nlohmann::json meta = {{"w", r.width},
                           {"h", r.height},
                           {"ox", r.images->a->originX},
                           {"oy", r.images->a->originY},
                           {"channels", r.channelNames}};
    nlohmann::json pixels = {{"a", embedPixels(*r.images->a)}, {"b", embedPixels(*r.images->b)}};
    o << "<script>\nconst META=" << scriptSafe(meta.dump()) << ";\nconst PIXELS=" << scriptSafe(pixels.dump())
      << ";\n</script>\n<script>" << kScript << "</script>\n";
  }
  o << "<h2>report.json</h2>\n<pre>" << escapeHtml(report.dump(2)) << "</pre>\n</body></html>\n";
  return o.str();
}

}  // namespace tessera::verify
