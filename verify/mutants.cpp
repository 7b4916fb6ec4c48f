#include "verify/mutants.h"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>

#include "base/atomic_file.h"
#include "base/error.h"
#include "raster/cpu_backend.h"
#include "verify/html_escape.h"
#include "verify/judge.h"

namespace tessera::verify {

namespace {

using Clock = std::chrono::steady_clock;

// One GL run of a frame, judged image by image: the unexplained pixels and the fail maps.
struct GlVerdict {
  uint64_t unexplained = 0;
  std::vector<std::vector<uint8_t>> failMaps;  // per presented image: 0 exact, 1 explained, 2 unexplained
};

GlVerdict judgeGl(const MutantFrame& f, const CpuBackend& oracle, gl::GlBackend& gl) {
  gl.execute(f.list, f.name);
  const auto presented = oracle.presented();
  const auto glPresented = gl.presented();
  if (presented.size() != glPresented.size())
    throw Error(f.name + ": the oracle presents " + std::to_string(presented.size()) + " images, GL " +
                std::to_string(glPresented.size()));
  GlVerdict v;
  for (size_t i = 0; i < presented.size(); ++i) {
    const PresentedImage& p = presented[i];
    const Judgement j = judge(*oracle.texture(p.texture), p.level, p.layer, gl.readImage(glPresented[i]));
    v.unexplained += j.unexplained;
    v.failMaps.push_back(j.failMap);
  }
  return v;
}

// Pixels unexplained in `m` that the unmodified run `base` did not leave unexplained.
uint64_t newlyUnexplained(const GlVerdict& m, const GlVerdict& base) {
  uint64_t n = 0;
  for (size_t i = 0; i < m.failMaps.size(); ++i)
    for (size_t k = 0; k < m.failMaps[i].size(); ++k) n += m.failMaps[i][k] == 2 && base.failMaps[i][k] != 2;
  return n;
}

nlohmann::json toJson(const MutantsResult& r) {
  nlohmann::json mutants = nlohmann::json::array();
  for (const MutantRow& row : r.rows) {
    nlohmann::json by = nlohmann::json::object(), fresh = nlohmann::json::object();
    for (size_t f = 0; f < r.frames.size(); ++f) {
      by[r.frames[f]] = row.unexplained[f];
      fresh[r.frames[f]] = row.newUnexplained[f];
    }
    const gl::Mutation& m = *row.mutation;
    nlohmann::json j = {{"name", m.name},
                        {"imitates", m.imitates},
                        {"kind", m.kind},
                        {"change", m.change},
                        {"status", row.status},
                        {"killed_by", row.killedBy},
                        {"unexplained_by_scene", by},
                        {"new_unexplained_by_scene", fresh}};
    if (!m.equivalent.empty()) j["equivalence_argument"] = m.equivalent;
    if (row.verdictTooStrict) j["verdict_stricter_than_gl"] = true;
    if (row.killedByPin) j["killed_by_documented_pin"] = m.pin;
    mutants.push_back(j);
  }
  nlohmann::json alarms = nlohmann::json::object();
  for (size_t f = 0; f < r.frames.size(); ++f) alarms[r.frames[f]] = r.falseAlarms[f];
  size_t killed = 0, survived = 0, equivalent = 0;
  for (const MutantRow& row : r.rows) {
    killed += row.status == "killed";
    survived += row.status == "survived";
    equivalent += row.status == "equivalent";
  }
  return {{"mutants", mutants},
          {"scenes", r.frames},
          {"false_alarms", alarms},
          {"killed", killed},
          {"survived", survived},
          {"equivalent", equivalent},
          {"killed_percent", r.killedPercent},
          {"killed_percent_meaning", "killed / mutants not catalogued as equivalent"},
          {"kill_rule",
           "a scene kills a mutant when GL under the mutant has an unexplained pixel that the unmodified "
           "backend did not have"},
          {"passed", r.passed()},
          {"runtime_seconds", r.runtimeSeconds}};
}

}  // namespace

bool MutantsResult::passed() const {
  for (uint64_t a : falseAlarms)
    if (a) return false;
  for (const MutantRow& r : rows)
    if (r.status == "survived" || (r.verdictTooStrict && !r.killedByPin)) return false;
  return true;
}

MutantsResult runMutants(const std::vector<MutantFrame>& frames, const std::vector<const gl::Mutation*>& mutations,
                         gl::GlBackend& gl, const MutantsOptions& o) {
  const auto t0 = Clock::now();
  auto say = [&](const std::string& s) {
    if (o.progress) o.progress(s);
  };
  MutantsResult r;
  // The oracle once per frame, in provenance mode: every GL run of that frame is judged against it.
  std::vector<std::unique_ptr<CpuBackend>> oracles;
  for (const MutantFrame& f : frames) {
    r.frames.push_back(f.name);
    auto b = std::make_unique<CpuBackend>(RenderOptions{o.threads, true, o.limits});
    b->execute(f.list, f.name);
    oracles.push_back(std::move(b));
    say("oracle " + f.name);
  }
  gl.setMutation(nullptr);
  std::vector<GlVerdict> base;
  for (size_t f = 0; f < frames.size(); ++f) {
    base.push_back(judgeGl(frames[f], *oracles[f], gl));
    r.falseAlarms.push_back(base.back().unexplained);
    say(fmt::format("unmodified x {}: {} unexplained", frames[f].name, base.back().unexplained));
  }
  size_t killed = 0, counted = 0;
  for (size_t k = 0; k < mutations.size(); ++k) {
    const gl::Mutation* m = mutations[k];
    gl.setMutation(m);
    MutantRow row;
    row.mutation = m;
    for (size_t f = 0; f < frames.size(); ++f) {
      GlVerdict v;
      try {
        v = judgeGl(frames[f], *oracles[f], gl);
      } catch (...) {
        gl.setMutation(nullptr);
        throw;
      }
      const uint64_t fresh = newlyUnexplained(v, base[f]);
      row.unexplained.push_back(v.unexplained);
      row.newUnexplained.push_back(fresh);
      if (fresh) row.killedBy.push_back(frames[f].name);
      say(fmt::format("[{}/{}] {} x {}: {} unexplained{}", k + 1, mutations.size(), m->name, frames[f].name,
                      v.unexplained, fresh ? " (killed)" : ""));
    }
    // A mutant catalogued as equivalent stays "equivalent" even when a scene kills it: that kill is
    // the verdict rejecting behaviour GL allows (a false alarm a conforming GL could raise), flagged
    // apart instead of counted as a catch.
    row.status = !m->equivalent.empty() ? "equivalent" : !row.killedBy.empty() ? "killed" : "survived";
    row.verdictTooStrict = !m->equivalent.empty() && !row.killedBy.empty();
    row.killedByPin = row.verdictTooStrict && !m->pin.empty();
    killed += row.status == "killed";
    counted += row.status != "equivalent";
    r.rows.push_back(std::move(row));
  }
  gl.setMutation(nullptr);
  r.killedPercent = counted ? 100.0 * double(killed) / double(counted) : 100.0;
  r.runtimeSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
  r.json = toJson(r);
  return r;
}

void writeMutantsReport(const MutantsResult& r, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create the report directory: " + ec.message());
  writeFileAtomically(dir + "/report.json", r.json.dump(2) + "\n");

  std::string head = "<tr><th>mutant</th><th>imitates</th><th>kind</th><th>status</th>";
  for (const std::string& f : r.frames) head += "<th>" + escapeHtml(f) + "</th>";
  head += "<th>change / equivalence argument</th></tr>";
  std::string rows = "<tr class=base><td>unmodified backend</td><td>(false alarms)</td><td></td><td></td>";
  for (uint64_t a : r.falseAlarms) rows += fmt::format("<td class={}>{}</td>", a ? "alarm" : "clean", a);
  rows += "<td>unexplained pixels of GL without a mutation: must be 0</td></tr>\n";
  for (const MutantRow& row : r.rows) {
    const gl::Mutation& m = *row.mutation;
    rows += fmt::format("<tr><td><b>{}</b></td><td>{}</td><td>{}</td><td class={}>{}{}</td>", escapeHtml(m.name),
                        escapeHtml(m.imitates), escapeHtml(m.kind),
                        row.verdictTooStrict && !row.killedByPin ? "alarm" : row.status, row.status,
                        row.killedByPin           ? " — killed by a documented pin: " + escapeHtml(m.pin)
                        : row.verdictTooStrict ? std::string(" — but killed: the verdict is stricter than GL here")
                                               : std::string());
    for (size_t f = 0; f < r.frames.size(); ++f) {
      const bool kill = row.newUnexplained[f] > 0;
      rows += fmt::format(
          "<td class={} title='{} unexplained, {} of them new (not unexplained without the mutant)'>{}</td>",
          kill ? "kill" : "live", row.unexplained[f], row.newUnexplained[f], row.unexplained[f]);
    }
    rows += "<td>" + escapeHtml(m.change);
    if (!m.equivalent.empty()) rows += "<br><i>equivalent: " + escapeHtml(m.equivalent) + "</i>";
    rows += "</td></tr>\n";
  }
  const std::string html = fmt::format(
      R"(<!doctype html><meta charset=utf-8><title>Tessera mutants</title>
<style>body{{font-family:sans-serif;margin:1em}}table{{border-collapse:collapse}}td,th{{border:1px solid #aaa;padding:2px 6px;vertical-align:top}}
td.kill{{background:#8d8;font-weight:bold}}td.live{{color:#888}}td.killed{{background:#8d8}}td.survived{{background:#f88}}
td.equivalent{{background:#ddf}}td.alarm{{background:#f55}}td.clean{{background:#dfd}}tr.base{{background:#f4f4f4}}</style>
<h1>Mutation testing of the cross-check</h1>
<p><b>{verdict}</b> · killed {killed_percent:.1f}% ({killed} killed, {survived} survived, {equivalent} equivalent) ·
runtime {runtime:.1f} s · GL: {renderer}{strict}</p>
<p>A cell is the number of unexplained pixels of GL under the mutant in that scene; a green cell is a kill: an
unexplained pixel that the unmodified backend does not have. The first row holds the unmodified backend's own
unexplained pixels (false alarms). A mutant catalogued as equivalent (GL allows what it does) that a scene still
kills is marked red: there the verdict would reject a conforming GL. See docs/mutants.md.</p>
<table>{head}
{rows}</table>
<h2>JSON</h2><pre>{json}</pre>
)",
      fmt::arg("verdict", r.passed() ? "PASS" : "FAIL"), fmt::arg("killed_percent", r.killedPercent),
      fmt::arg("killed", r.json.value("killed", 0)), fmt::arg("survived", r.json.value("survived", 0)),
      fmt::arg("equivalent", r.json.value("equivalent", 0)), fmt::arg("runtime", r.runtimeSeconds),
      fmt::arg("renderer", escapeHtml(r.json.contains("gl_info") ? r.json["gl_info"].value("gl_renderer", "?") : "?")),
      fmt::arg("strict", r.json.value("strict", false) ? " (--strict)" : ""), fmt::arg("head", head),
      fmt::arg("rows", rows), fmt::arg("json", escapeHtml(r.json.dump(1))));
  writeFileAtomically(dir + "/index.html", html);
}

}  // namespace tessera::verify
