#include "verify/crosscheck_report.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "raster/image_io.h"
#include "base/atomic_file.h"
#include "verify/compare_report.h"

namespace tessera::verify {

namespace {

double channel(Format f, const std::vector<uint8_t>& px, size_t i, int c) {
  const size_t bpt = texelBytes(f);
  if (isUnorm(f)) return px[i * bpt + size_t(c)];
  if (isFloat(f)) {
    float v;
    std::memcpy(&v, &px[i * bpt + 4 * size_t(c)], 4);
    return v;
  }
  uint32_t u;
  std::memcpy(&u, &px[i * bpt + 4 * size_t(c)], 4);
  return u;
}

// Display version of a target's pixels as opaque RGBA8.
std::vector<uint8_t> display(Format f, const std::vector<uint8_t>& px, size_t n) {
  std::vector<uint8_t> out(n * 4, 255);
  for (size_t i = 0; i < n; ++i) {
    uint8_t* o = &out[i * 4];
    if (f == Format::R32UI) {
      const uint32_t v = uint32_t(channel(f, px, i, 0));
      // A stable hash colour per id; the background id 0xffffffff is black.
      const uint32_t h = v == 0xffffffffu ? 0u : (v * 2654435761u) | 0x404040u;
      o[0] = uint8_t(h >> 16), o[1] = uint8_t(h >> 8), o[2] = uint8_t(h);
      continue;
    }
    const int ch = channelCount(f);
    for (int c = 0; c < 3; ++c) {
      const int src = ch == 1 ? 0 : c;
      if (src >= ch) {
        o[c] = 0;
        continue;
      }
      const double v = channel(f, px, i, src);
      o[c] = isUnorm(f) ? uint8_t(v) : uint8_t(std::isnan(v) ? 255 : std::clamp(v, 0.0, 1.0) * 255.0 + 0.5);
    }
  }
  return out;
}

int bin(double d) {
  if (!(d > 0)) return 0;
  if (d <= 1) return 1;
  if (d <= 2) return 2;
  int b = 3;
  for (double edge = 4; b < 9 && d > edge; edge *= 2) ++b;
  return b;
}

// Colours of the class overlay: the lowest set class bit picks the colour.
constexpr Rgba kClassColors[kClassCount] = {
    {255, 200, 0, 255},  {255, 120, 0, 255}, {0, 160, 255, 255},  {0, 220, 160, 255}, {160, 0, 255, 255},
    {255, 0, 200, 255},  {120, 120, 0, 255}, {80, 200, 255, 255}, {0, 120, 80, 255},  {200, 160, 255, 255},
    {140, 255, 140, 255}, {255, 140, 140, 255}, {0, 200, 200, 255}, {200, 80, 40, 255}};


std::string jsonArray(Format f, const std::vector<uint8_t>& px, size_t n) {
  std::string s = "[";
  const int ch = channelCount(f);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < ch; ++c) {
      if (i || c) s += ',';
      const double v = channel(f, px, i, c);
      s += std::isfinite(v) ? fmt::format("{}", v) : "null";
    }
  return s + "]";
}

}  // namespace

void writeCrosscheckReport(const CrosscheckResult& result, const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create the report directory: " + ec.message());
  writeFileAtomically(dir + "/report.json", result.json.dump(2) + "\n");

  std::string sections, data;
  for (size_t k = 0; k < result.images.size(); ++k) {
    const ImageVerdict& v = result.images[k];
    const Judgement& j = v.judgement;
    const size_t n = size_t(j.width) * size_t(j.height);
    const std::string p = fmt::format("img{}_", k);
    writePngRGBA8(dir + "/" + p + "oracle.png", j.width, j.height, display(j.format, v.oracle, n).data());
    writePngRGBA8(dir + "/" + p + "gl.png", j.width, j.height, display(j.format, v.other, n).data());
    std::vector<uint8_t> heat(n * 4, 255), cls(n * 4, 255);
    for (size_t i = 0; i < n; ++i) {
      double worst = 0;
      for (int c = 0; c < j.channels; ++c) {
        const double d = std::fabs(channel(j.format, v.oracle, i, c) - channel(j.format, v.other, i, c));
        worst = std::max(worst, std::isfinite(d) ? d : 1e9);
      }
      const Rgba h = heatColor(bin(worst));
      std::memcpy(&heat[i * 4], h.data(), 4);
      Rgba c{60, 60, 60, 255};
      if (j.failMap[i] == 2) {
        c = {255, 0, 0, 255};
      } else if (j.classMap[i]) {
        const int b = std::countr_zero(uint32_t(j.classMap[i]));
        c = kClassColors[b];
        if (j.failMap[i] == 0) c = {uint8_t(c[0] / 2), uint8_t(c[1] / 2), uint8_t(c[2] / 2), 255};  // classed but exact
      }
      std::memcpy(&cls[i * 4], c.data(), 4);
    }
    writePngRGBA8(dir + "/" + p + "heat.png", j.width, j.height, heat.data());
    writePngRGBA8(dir + "/" + p + "classes.png", j.width, j.height, cls.data());
    const RgbaCanvas hist = histogramChart(j.histogram);
    writePngRGBA8(dir + "/" + p + "histogram.png", hist.width(), hist.height(), hist.data());

    const nlohmann::json jj = toJson(j);
    std::string rows;
    for (int b = 0; b < kClassCount; ++b) {
      const nlohmann::json& pc = jj["per_class"][std::string(ambiguityClassName(b))];
      rows += fmt::format(
          "<tr><td><span class=sw style='background:rgb({},{},{})'></span>{}</td><td>{}</td><td>{}</td>"
          "<td>{:.4f}</td><td>{}</td><td>{}</td><td>{:.3f}</td><td>{}</td><td>{}</td></tr>",
          kClassColors[b][0], kClassColors[b][1], kClassColors[b][2], ambiguityClassName(b), j.classPixels[size_t(b)],
          j.classExplained[size_t(b)], pc["fraction"].get<double>(), pc["mean_width"].dump(), pc["max_width"].dump(),
          pc["mean_candidates"].get<double>(), pc["max_candidates"].dump(), pc["fallbacks"].dump());
    }
    sections += fmt::format(
        "<h2>{name} — {fmt} {w}x{h}: {verdict}</h2>"
        "<p>exact {exact:.3f}% · classed {classed} · explained {expl} · <b>unexplained {unexpl}</b> · max |Δ| {maxd} · "
        "PSNR {psnr}</p>"
        "<div class=row><figure><img id=o{k} src='{p}oracle.png'><figcaption>oracle</figcaption></figure>"
        "<figure><img id=g{k} src='{p}gl.png'><figcaption>GL</figcaption></figure>"
        "<figure><img src='{p}heat.png'><figcaption>|Δ| heat map</figcaption></figure>"
        "<figure><img src='{p}classes.png'><figcaption>classes (dim = classed but exact, red = unexplained)</figcaption></figure>"
        "<figure><img id=alt{k} src='{p}oracle.png'><figcaption><button onclick='flip({k})'>alternate oracle / GL</button> "
        "<span id=altl{k}>oracle</span></figcaption></figure></div>"
        "<p class=insp id=insp{k}>click or hover a pixel to inspect it</p>"
        "<p><img src='{p}histogram.png' style='width:auto'><br>error histogram (|Δ| per pixel, largest channel, log scale)</p>"
        "<table><tr><th>class</th><th>pixels</th><th>explained differences</th><th>fraction</th>"
        "<th>mean width</th><th>max width</th><th>mean candidates</th><th>max candidates</th><th>fallbacks</th></tr>"
        "{rows}</table><p>candidate sets that fell back to their hull: {fallbacks} · pixels with lookup candidates: "
        "{lforked} · lookups used as their hull: {lfallbacks}</p>",
        fmt::arg("name", v.name), fmt::arg("fmt", formatName(j.format)), fmt::arg("w", j.width), fmt::arg("h", j.height),
        fmt::arg("verdict", j.passed() ? "PASS" : "FAIL"), fmt::arg("exact", j.exactPercent()),
        fmt::arg("classed", j.classed), fmt::arg("expl", j.explained), fmt::arg("unexpl", j.unexplained),
        fmt::arg("maxd", jj["max_abs_diff"].dump()), fmt::arg("psnr", jj["psnr_db"].dump()), fmt::arg("k", k),
        fmt::arg("p", p), fmt::arg("rows", rows), fmt::arg("fallbacks", j.fallbacks),
        fmt::arg("lforked", j.lookupForked), fmt::arg("lfallbacks", j.lookupFallbacks));
    if (n <= (1u << 20)) {
      std::string classes = "[";
      for (size_t i = 0; i < n; ++i) {
        if (i) classes += ',';  // not (i ? "," : "") + ...: GCC 12 warns falsely there (-Wrestrict, GCC bug 105329)
        classes += std::to_string(j.classMap[i]);
      }
      classes += "]";
      data += fmt::format("D[{}]={{w:{},h:{},ch:{},o:{},g:{},lo:{},hi:{},c:{}}};\n", k, j.width, j.height, j.channels,
                          jsonArray(j.format, v.oracle, n), jsonArray(j.format, v.other, n),
                          jsonArray(j.format, v.lo, n), jsonArray(j.format, v.hi, n), classes);
    }
  }
  std::string names = "[";
  for (int b = 0; b < kClassCount; ++b) names += fmt::format("{}\"{}\"", b ? "," : "", ambiguityClassName(b));
  names += "]";
  const std::string html = fmt::format(
      R"(<!doctype html><meta charset=utf-8><title>Tessera crosscheck: {frame}</title>
<style>body{{font-family:sans-serif;margin:1em}}.row{{display:flex;flex-wrap:wrap;gap:8px}}
figure{{margin:0}}img{{image-rendering:pixelated;width:{zoom}px;border:1px solid #888;cursor:crosshair}}
table{{border-collapse:collapse;margin:.5em 0}}td,th{{border:1px solid #aaa;padding:2px 6px}}
.sw{{display:inline-block;width:10px;height:10px;margin-right:4px}}.insp{{font-family:monospace;background:#f4f4f4;padding:4px}}</style>
<h1>Oracle vs GL: {frame}</h1>
<p><b>{verdict}</b> · exact match {exact:.3f}% of {pixels} pixels · unexplained {unexpl} · counters equal: {counters}</p>
<pre>{first}</pre>
{sections}
<h2>Summary JSON</h2><pre>{json}</pre>
<script>
const D={{}};const NAMES={names};
{data}
function flip(k){{const a=document.getElementById('alt'+k),l=document.getElementById('altl'+k);
 const gl=a.src.endsWith('gl.png');a.src=a.src.replace(gl?'gl.png':'oracle.png',gl?'oracle.png':'gl.png');l.textContent=gl?'oracle':'GL';}}
function inspect(k,ev){{const d=D[k];const out=document.getElementById('insp'+k);if(!d){{out.textContent='(pixel data not embedded: image too large)';return;}}
 const r=ev.target.getBoundingClientRect();const x=Math.floor((ev.clientX-r.left)*d.w/r.width),y=Math.floor((ev.clientY-r.top)*d.h/r.height);
 if(x<0||y<0||x>=d.w||y>=d.h)return;const i=y*d.w+x,s=i*d.ch;const sl=a=>JSON.stringify(a.slice(s,s+d.ch));
 const c=d.c[i];const cn=NAMES.filter((n,b)=>c>>b&1);
 out.textContent=`x=${{x}} y=${{y}} (image rows from the top) oracle=${{sl(d.o)}} GL=${{sl(d.g)}} legal [lo,hi]=${{sl(d.lo)}}..${{sl(d.hi)}} classes=${{cn.join(' ')||'none (must match exactly)'}}`;}}
document.querySelectorAll('img').forEach(im=>{{const k=parseInt((im.getAttribute('src').match(/img(\d+)_(oracle|gl|heat|classes)/)||[])[1]);
 if(!isNaN(k)){{im.addEventListener('mousemove',e=>inspect(k,e));im.addEventListener('click',e=>inspect(k,e));}}}});
</script>
)",
      fmt::arg("frame", result.json.value("frame", "")), fmt::arg("zoom", 320),
      fmt::arg("verdict", result.passed ? "PASS" : "FAIL"), fmt::arg("exact", result.json.value("exact_match_percent", 0.0)),
      fmt::arg("pixels", result.json.value("pixels", 0)), fmt::arg("unexpl", result.json.value("unexplained", 0)),
      fmt::arg("counters", result.json.contains("counters") ? result.json["counters"]["equal"].dump() : "n/a"),
      fmt::arg("first", result.json.contains("first_diverging_draw") ? "first diverging draw: " + result.json["first_diverging_draw"].dump(1) : ""),
      fmt::arg("sections", sections), fmt::arg("json", result.json.dump(1)), fmt::arg("names", names),
      fmt::arg("data", data));
  writeFileAtomically(dir + "/index.html", html);
}

}  // namespace tessera::verify
