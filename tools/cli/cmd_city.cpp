// `tessera city`: writes a deterministic synthetic city (Buchholz's "berlin" / "chemnitz" test scenes,
// model/city_gen.h) as a glTF 2.0 file with its textures (or, with --split-per-building, one glTF per
// building and a scene manifest), and prints a JSON summary.
#include <chrono>
#include <cstdio>
#include <memory>

#include "model/city_gen.h"
#include "model/model.h"
#include "base/error.h"
#include "tools/cli/commands.h"
#include "tools/cli/output_directory.h"

namespace tessera::cli {

namespace {

struct CityArgs {
  std::string preset = "berlin";
  uint32_t buildings = 0;
  uint64_t seed = 1;
  uint32_t textureSize = 512;
  std::string format = "png";
  std::string outDir;
  bool quiet = false;
  bool loadBack = false;
  bool split = false, lightMap = false;
};

void runCity(const CityArgs& a) {
  model::CityOptions o;
  o.preset = model::parseCityPreset(a.preset);
  o.buildings = a.buildings;
  o.seed = a.seed;
  o.textureSize = a.textureSize;
  if (a.format != "png" && a.format != "jpg") throw Error("--format '" + a.format + "': expected png or jpg");
  o.format = a.format == "jpg" ? model::CityImageFormat::Jpg : model::CityImageFormat::Png;
  prepareOutputDirectory(a.outDir, "-o");
  o.outDir = a.outDir;
  o.progress = !a.quiet;
  o.splitPerBuilding = a.split;
  o.lightMap = a.lightMap;
  const model::CitySummary s = model::generateCity(o);
  nlohmann::json j = s.toJson();
  j["preset"] = a.preset;
  j["seed"] = a.seed;
  j["texture_size"] = a.textureSize;
  j["format"] = a.format;
  if (a.loadBack) {  // read the file back the way a consumer would (textures stay undecoded)
    const auto t0 = std::chrono::steady_clock::now();
    const model::Model m = model::loadModel(s.gltf);
    j["load_back"] = {{"time_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()},
                      {"meshes", m.meshes.size()},
                      {"materials", m.materials.size()},
                      {"textures", m.textures.size()},
                      {"triangles", m.triangleCount()}};
    if (m.textures.size() != s.textures || m.triangleCount() != s.triangles)
      throw Error(s.gltf + ": reading it back gave " + std::to_string(m.textures.size()) + " textures and " +
                  std::to_string(m.triangleCount()) + " triangles instead of " + std::to_string(s.textures) + " and " +
                  std::to_string(s.triangles));
  }
  std::printf("%s\n", j.dump(2).c_str());
}

}  // namespace

void addCityCommand(CLI::App& app) {
  auto a = std::make_shared<CityArgs>();
  auto* city = app.add_subcommand(
      "city",
      "Write a synthetic city as glTF 2.0 with its textures: 'berlin' (N block buildings, one facade texture "
      "each, thesis: 10,000) or 'chemnitz' (irregular detail, ~2,000 textures, ~300k triangles, RGBA parts, "
      "2000x texture repeats); deterministic for a seed; prints a JSON summary");
  city->add_option("--preset", a->preset, "berlin or chemnitz")->required();
  city->add_option("--buildings", a->buildings, "Number of buildings (default: berlin 10000, chemnitz 400)")
      ->check(CLI::Range(1u, 1000000u));
  city->add_option("--seed", a->seed, "Seed; the same seed and options give the same bytes")->capture_default_str();
  city->add_option("--texture-size", a->textureSize,
                   "Berlin facade size; chemnitz scales its 64..512 sizes by this / 512")
      ->capture_default_str()
      ->check(CLI::Range(8u, 8192u));
  city->add_option("--format", a->format, "png (zlib level 1) or jpg (quality 90; RGBA textures stay PNG)")
      ->capture_default_str();
  city->add_option("-o,--output", a->outDir, "Output directory (created if missing)")->required();
  city->add_flag("--quiet", a->quiet, "No progress lines on stderr");
  city->add_flag("--load-back", a->loadBack,
                 "Read the written glTF back with the model loader and report its counts and time");
  city->add_flag("--split-per-building", a->split,
                 "Write one glTF per building (and one for the ground) under DIR/parts/ and the scene manifest "
                 "DIR/<preset>.json placing them, instead of DIR/<preset>.gltf (docs/model-import.md)");
  city->add_flag("--light-map", a->lightMap,
                 "Also a light-map layer: DIR/lightmap.png (grey, darker towards the bottom of each texture repeat) as every "
                 "textured material's glTF occlusionTexture on texCoord 0, the atlas tree's layer 1 (thesis 5.1.3)");
  city->callback([a] { runCity(*a); });
}

}  // namespace tessera::cli
