#include "config/config.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <toml++/toml.h>
#include <nlohmann/json.hpp>

#include "config/config_scene.h"
#include "config/config_technique.h"
#include "config/config_toml.h"
#include "config/cost_model_file.h"
#include "config/scene_files.h"
#include "core/atomic_write.h"
#include "core/data_paths.h"
#include "core/error.h"
#include "gl/embedded_files.h"
#include "scene/relief_asset.h"
#include "technique/technique.h"

namespace rl {

namespace fs = std::filesystem;
using json = nlohmann::json;

int resolve_texture_res(const SceneDesc& scene, int texture_res) {
  return texture_res > 0 ? texture_res : scene.relief.native.longer();
}

namespace {

// [sweep] cost_model: the GPU cost model the rows' model_frame_ms comes from, the default one
// unless the config names another (config/cost_model_file.h).
void parse_cost_model(const toml::table* sweep, const Src& src, const std::string& base_dir,
                      SweepConfig& c) {
  const toml::node* v = sweep ? sweep->get("cost_model") : nullptr;
  c.cost_model_name = v ? string_of(*v, src, "cost_model") : kDefaultCostModel;
  c.cost_model = load_cost_model(c.cost_model_name, base_dir, v ? src.at(*v) : src.file);
}

// Azimuths a full turn apart are one view: 0, 360 and -360 were three cells of it. In [0, 360)
// they are one, which the cells then hold once, as they do a repeated elevation.
void normalize_azimuths(std::vector<View>& views) {
  for (View& v : views) {
    double az = std::fmod(v.azimuth_deg, 360.0);
    if (az < 0) az += 360.0;
    // -1e-15 + 360 rounds to 360; fmod(-360, 360) is -0, a key apart from 0.
    v.azimuth_deg = (az == 360.0 || az == 0.0) ? 0.0 : az;
  }
}

// [sweep]: the name, views, viewports, texture sizes, timing and outputs; the views are the
// elevations x azimuths unless 'views' lists them.
void parse_sweep_table(const toml::table& root, const Src& src, SweepConfig& c) {
  std::vector<double> elevations = {45}, azimuths = {0};
  if (auto* n = root.get("sweep")) {
    const toml::table* t = n->as_table();
    if (!t) fail(src.at(*n), "[sweep] must be a table");
    check_keys(*t,
               {"name", "elevations", "azimuths", "views", "viewports", "texture_res", "frames",
                "warmup", "heat_map_scale", "truth_tolerance", "footprint_samples", "images",
                "gbuffers", "cost_model", "op_count_stride"},
               src, "[sweep]");
    if (auto* v = t->get("name")) c.name = plain_name(*v, src, "name");
    if (auto* v = t->get("elevations")) elevations = number_list(*v, src, "elevations");
    if (auto* v = t->get("azimuths")) azimuths = number_list(*v, src, "azimuths");
    // Negative elevations look from below: only relief impostors are seen from there.
    // Below 0.1 degrees a view sees the relief edge-on: no pixel measures anything.
    auto elevation_ok = [](double e) { return std::abs(e) >= 0.1 && std::abs(e) <= 90; };
    for (double e : elevations)
      if (!elevation_ok(e))
        fail(src.at(*t->get("elevations")),
             "elevations must be in [0.1, 90] degrees (or [-90, -0.1] for relief impostors), "
             "got " +
                 format_number(e));
    for (double a : azimuths)
      if (!(a >= -360 && a <= 360))
        fail(src.at(*t->get("azimuths")),
             "azimuths must be in [-360, 360] degrees, got " + format_number(a));
    if (auto* v = t->get("views")) {
      const toml::array* a = v->as_array();
      if (!a) fail(src.at(*v), "'views' must be an array of [elevation, azimuth] pairs");
      for (const toml::node& e : *a) {
        std::vector<double> pair = number_list(e, src, "views");
        if (pair.size() != 2 || !elevation_ok(pair[0]) || !(pair[1] >= -360 && pair[1] <= 360))
          fail(src.at(e),
               "each view must be [elevation in [0.1, 90] (or [-90, -0.1] for impostors), "
               "azimuth in [-360, 360]]");
        c.views.push_back({pair[0], pair[1]});
      }
    }
    if (auto* v = t->get("viewports")) {
      const toml::array* a = v->as_array();
      if (!a)
        fail(src.at(*v), "'viewports' must be an array of sizes (256) or [width, height] pairs");
      for (const toml::node& e : *a) {
        std::vector<double> wh = number_list(e, src, "viewports");
        if (wh.size() == 1) wh.push_back(wh[0]);
        if (wh.size() != 2 || wh[0] < 8 || wh[1] < 8 || wh[0] > 8192 || wh[1] > 8192 ||
            wh[0] != std::floor(wh[0]) || wh[1] != std::floor(wh[1]))
          fail(src.at(e), "each viewport must be a size or [width, height] in 8..8192");
        c.viewports.push_back({int(wh[0]), int(wh[1])});
      }
    }
    if (auto* v = t->get("texture_res")) {
      for (double r : number_list(*v, src, "texture_res")) {
        if (r != std::floor(r) || r < 0 || r > 8192 || r == 1)
          fail(src.at(*v), "texture_res must be 0 (native) or an integer in [2, 8192], got " +
                               std::to_string(r));
        c.texture_res.push_back(int(r));
      }
    }
    if (auto* v = t->get("frames")) c.frames = positive_int(*v, src, "frames", 1, 1000);
    if (auto* v = t->get("warmup")) c.warmup = positive_int(*v, src, "warmup", 0, 100);
    if (auto* v = t->get("heat_map_scale")) {
      c.heat_map_scale = number_in(*v, src, "heat_map_scale", 1e-3, 1e3);
    }
    if (auto* v = t->get("truth_tolerance")) {
      c.truth_tolerance = number(*v, src, "truth_tolerance");
      if (!(c.truth_tolerance > 0 && c.truth_tolerance < 1))
        fail(src.at(*v), "'truth_tolerance' must be in (0, 1)");
    }
    if (auto* v = t->get("footprint_samples"))
      c.footprint_samples = positive_int(*v, src, "footprint_samples", 1, 8);
    if (auto* v = t->get("images")) c.write_images = boolean_of(*v, src, "images");
    if (auto* v = t->get("gbuffers")) c.write_gbuffers = boolean_of(*v, src, "gbuffers");
    if (auto* v = t->get("op_count_stride"))
      c.op_count_stride = positive_int(*v, src, "op_count_stride", 1, 16);
  }
  if (c.views.empty())
    for (double e : elevations)
      for (double a : azimuths) c.views.push_back({e, a});
  normalize_azimuths(c.views);
  if (c.viewports.empty()) c.viewports.push_back({256, 256});
  if (c.texture_res.empty()) c.texture_res.push_back(0);
}

// The names a table's rows and columns or a plot's groups may use: the sweep's fields and
// every registered technique's parameters.
std::set<std::string> sweep_fields() {
  std::set<std::string> fields = {"technique",   "scene",    "elevation_deg", "azimuth_deg",
                                  "texture_res", "viewport", "bake_axis"};
  for (const auto& name : TechniqueRegistry::instance().names())
    for (const ParamSpec& p : TechniqueRegistry::instance().find(name)->info.params)
      fields.insert(p.name);
  return fields;
}

// A parsed scene completed from its files (sizes, proportions, hashes), checked against the
// sweep's views and sizes, and entered in the canonical description; a three-view scene's bake
// along another axis first gets that scene's light and objects carried into its frame.
void enter_scene(SweepConfig& c, json& canon, std::set<std::string>& scene_names,
                 ParsedScene parsed, const toml::node& n, const Src& src,
                 const SceneDesc* three_view_scene = nullptr) {
  read_scene_files(parsed);
  json& sc = parsed.canon;
  if (three_view_scene) {
    // A bake along another axis is lit by the scene's own light, carried into its frame.
    SceneDesc& bake = parsed.scene;
    bake.light_position =
        carry_to_bake(three_view_scene->light_position, three_view_scene->relief.mesh_up,
                      three_view_scene->depth, bake.relief.mesh_up, bake.depth);
    sc["light"] = {bake.light_position.x, bake.light_position.y, bake.light_position.z};
    // Its objects likewise (spheres and cubes: a turn between bakes keeps a cube axis-aligned).
    for (size_t i = 0; i < bake.objects.size(); ++i) {
      SceneObject& o = bake.objects[i];
      o.center = carry_to_bake(o.center, three_view_scene->relief.mesh_up, three_view_scene->depth,
                               bake.relief.mesh_up, bake.depth);
      for (int k = 0; k < 3; ++k) sc["objects"][i][1 + k] = o.center[k];
    }
  }
  c.scenes.push_back(parsed.scene);
  SceneDesc& scene = c.scenes.back();
  // Layers cost memory per texel and layer (7 floats baked, then 28 bytes uploaded).
  for (int res : c.texture_res) {
    // A meta-relief's layers scale with layer 0: one past the largest map is refused here, not
    // after minutes of building, naming the resolution it would have.
    for (size_t i = 0; i < scene.meta.layers.size(); ++i)
      if (const int side = meta_layer_resolution(scene, scene.meta.layers[i], res); side > 8192)
        fail(src.at(n), "scene '" + scene.name + "': meta_relief layer " + std::to_string(i + 1) +
                            " (" + std::to_string(scene.meta.layers[i].relief.native.longer()) +
                            " texels a side) scales with texture_res " +
                            (res ? std::to_string(res) : std::string("0 (native)")) + " to " +
                            std::to_string(side) +
                            " texels a side, past the largest map (8192): lower texture_res or "
                            "the layer's size");
    const MapSize size = scene.relief.size_at(res);
    if (scene.relief.layers > 0 &&
        double(size.width) * size.height * scene.relief.layers > double(1 << 26))
      fail(src.at(n), "scene '" + scene.name + "': " + std::to_string(size.width) + "x" +
                          std::to_string(size.height) + " texels x " +
                          std::to_string(scene.relief.layers) +
                          " layers exceeds 67,108,864 (e.g. 2048^2 x 8 or 4096^2 x 4)");
  }
  for (const View& v : c.views)
    if (v.elevation_deg < 0 && !scene.impostor() && !scene.in_cube())
      fail(src.at(n),
           "scene '" + scene.name + "' is seen from below (elevation " +
               std::to_string(v.elevation_deg) +
               "), which only relief impostors (a mesh with 'layers'), cell complexes and "
               "heightfield objects (a mesh with 'faces') can be; give it a sweep of its own");
  if (scene.framing == Framing::Fill) {
    // Lengthen the quad (whole tiles more) for the grazing-est view of the sweep.
    double min_el = 90, max_aspect = 0;
    for (const View& v : c.views) min_el = std::min(min_el, v.elevation_deg);
    for (const auto& [w, h] : c.viewports) max_aspect = std::max(max_aspect, double(w) / h);
    apply_fill_framing(scene, min_el, max_aspect);
    sc["size"] = scene.size;
    sc["tile"] = scene.tile;
  }
  if (!scene_names.insert(c.scenes.back().name).second)
    fail(src.at(n), "duplicate scene name '" + c.scenes.back().name + "'");
  canon["scenes"][c.scenes.back().name] = sc;
  c.scene_canonical[c.scenes.back().name] = sc.dump();
  c.scene_inputs[c.scenes.back().name] = parsed.inputs;
  c.scene_sites[c.scenes.back().name] = {parsed.sites.scene, parsed.sites.relief};
}

// One [[scene]]: parsed, then entered with, for a three-view impostor, its bakes along the two
// other axes (named "<scene>-along-<axis>", their cells picked by run/cells.h).
void add_scene(SweepConfig& c, json& canon, std::set<std::string>& scene_names,
               const toml::table& t, const toml::node& n, const Src& src,
               const std::string& base_dir) {
  const ParsedScene parsed = parse_scene(t, src, base_dir, n);
  const SceneDesc& scene = parsed.scene;
  if (scene.relief.three_views && !scene.impostor())
    fail(src.at(n), "scene '" + scene.name +
                        "': 'three_views' draws a relief impostor, which needs a flat base");
  for (const SceneObject& o : scene.objects)
    if (scene.relief.three_views && o.shape != "sphere" && o.shape != "cube")
      fail(src.at(n), "scene '" + scene.name + "': 'three_views' carries spheres and cubes into " +
                          "each bake's frame, not a mesh object (" + o.shape + "), which would " +
                          "need turning");
  if (scene.relief.three_views && scene.distance == 0)
    fail(src.at(n), "scene '" + scene.name +
                        "': 'three_views' needs a camera 'distance': fitted to each bake's quad "
                        "and depth, the camera would draw the object at three scales");
  enter_scene(c, canon, scene_names, parsed, n, src);
  if (!scene.relief.three_views) return;
  const SceneDesc entered = c.scenes.back();  // its depth read from the mesh
  for (int axis = 0; axis < 3; ++axis) {
    if (axis == entered.relief.mesh_up) continue;
    ParsedScene bake = parsed;
    bake.scene.relief.mesh_up = axis;
    bake.canon["relief"]["up"] = axis;
    bake.scene.name = scene.name + "-along-" + char('x' + axis);
    bake.canon["name"] = bake.scene.name;
    bake.scene.bake_of = scene.name;
    enter_scene(c, canon, scene_names, std::move(bake), n, src, &entered);
  }
}

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// A table's title: one line of at most 1000 characters (a newline would forge Markdown after
// the table's heading, and a title is printed in every table file and the report).
std::string table_title(const toml::node& n, const Src& src) {
  const std::string v = string_of(n, src, "title");
  const bool control = std::any_of(
      v.begin(), v.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
  if (control || v.size() > 1000)
    fail(src.at(n),
         "[[table]] 'title' must be one line of at most 1000 characters without "
         "control characters (got " +
             std::to_string(v.size()) + " characters" +
             (control ? ", with a line break or control character" : "") + ")");
  return v;
}

// [[table]]s, or the default table of the headline errors and costs by scene, view and
// setting.
void parse_tables(const toml::table& root, const Src& src, const std::set<std::string>& fields,
                  SweepConfig& c) {
  if (auto* n = root.get("table")) {
    const toml::array* tables = n->as_array();
    if (!tables) fail(src.at(*n), "tables are given as [[table]]");
    for (const toml::node& tn : *tables) {
      const toml::table* t = tn.as_table();
      if (!t) fail(src.at(tn), "[[table]] must be a table");
      check_keys(*t, {"file", "title", "rows", "columns", "values", "aggregate", "format"}, src,
                 "[[table]]");
      TableSpec spec;
      spec.file =
          c.tables.empty() ? "table.md" : "table-" + std::to_string(c.tables.size() + 1) + ".md";
      // A plain name of at most 64 characters: a path or an overlong name would only fail
      // when the tables are written, after everything was measured.
      if (auto* v = t->get("file")) spec.file = plain_name(*v, src, "file");
      const toml::node& at = t->get("file") ? *t->get("file") : tn;
      const auto& owned = run_owned_names();
      if (std::find(owned.begin(), owned.end(), spec.file) != owned.end())
        fail(src.at(at), "table 'file' \"" + spec.file +
                             "\" is a name the run writes itself; choose another (the run owns: " +
                             join_names(owned) + ")");
      for (const TableSpec& other : c.tables)
        if (other.file == spec.file)
          fail(src.at(at), "table 'file' \"" + spec.file +
                               "\" is already another [[table]]'s: the second would overwrite it");
      if (auto* v = t->get("title")) spec.title = table_title(*v, src);
      if (auto* v = t->get("rows")) spec.rows = string_list(*v, src, "rows");
      if (auto* v = t->get("columns")) spec.columns = string_list(*v, src, "columns");
      if (auto* v = t->get("values")) spec.values = string_list(*v, src, "values");
      if (auto* v = t->get("aggregate")) {
        spec.aggregate = string_of(*v, src, "aggregate");
        if (spec.aggregate != "mean" && spec.aggregate != "max")
          fail(src.at(*v), "[[table]] aggregate '" + spec.aggregate + "': use \"mean\" or \"max\"");
      }
      if (auto* v = t->get("format")) {
        spec.format = string_of(*v, src, "format");
        if (spec.format != "markdown" && spec.format != "latex")
          fail(src.at(*v),
               "[[table]] format '" + spec.format + "': use \"markdown\" (default) or \"latex\"");
        // A LaTeX table without a file name gets a .tex one.
        if (spec.format == "latex" && !t->get("file"))
          spec.file = spec.file.substr(0, spec.file.size() - 3) + ".tex";
      }
      if (spec.values.empty()) fail(src.at(tn), "[[table]] needs 'values' (metric names)");
      for (const std::string& v : spec.values)
        if (!is_measured(v))
          fail(src.at(tn),
               "[[table]] value '" + v + "' is not a measured column (" + measured_list() + ")");
      for (const auto* list : {&spec.rows, &spec.columns})
        for (const std::string& f : *list)
          if (!fields.count(f))
            fail(src.at(tn), "[[table]] field '" + f + "' is not a sweep field or parameter");
      c.tables.push_back(spec);
    }
  }
  if (c.tables.empty()) {
    TableSpec t;
    t.rows = {"scene", "elevation_deg", "technique"};
    for (const auto& ts : c.techniques) {
      std::vector<std::string> varied;
      for (const auto& [p, v] : ts.param_lists) varied.push_back(p);
      for (const ParamValues& set : ts.sets)
        for (const auto& [p, v] : set) varied.push_back(p);
      for (const std::string& p : varied)
        if (std::find(t.rows.begin(), t.rows.end(), p) == t.rows.end()) t.rows.push_back(p);
    }
    t.values = {"wrong_pct",    "pos_err_rmse",      "artifact_pct",        "psnr_db",
                "fetches_mean", "frag_fetches_mean", "warp_fetches_per_px", "gpu_frame_ms",
                "frame_ms"};
    c.tables.push_back(t);
  }
}

// [[plot]]s, or the default error-against-cost plot (output/pareto.h).
void parse_plots(const toml::table& root, const Src& src, const std::set<std::string>& fields,
                 SweepConfig& c) {
  if (auto* n = root.get("plot")) {
    const toml::array* plots = n->as_array();
    if (!plots) fail(src.at(*n), "plots are given as [[plot]]");
    for (const toml::node& pn : *plots) {
      const toml::table* t = pn.as_table();
      if (!t) fail(src.at(pn), "[[plot]] must be a table");
      check_keys(*t, {"x", "y", "group", "log_y"}, src, "[[plot]]");
      PlotSpec p;
      if (auto* v = t->get("x")) p.x = string_of(*v, src, "x");
      if (auto* v = t->get("y")) p.y = string_of(*v, src, "y");
      if (auto* v = t->get("group")) p.group = string_list(*v, src, "group");
      if (auto* v = t->get("log_y")) p.log_y = number_or_flag(*v, src, "log_y") != 0;
      for (const std::string& m : {p.x, p.y})
        if (!is_measured(m))
          fail(src.at(pn),
               "[[plot]] axis '" + m + "' is not a measured column (" + measured_list() + ")");
      for (const std::string& f : p.group)
        if (!fields.count(f))
          fail(src.at(pn), "[[plot]] group field '" + f + "' is not a sweep field or parameter");
      c.plots.push_back(p);
    }
  }
  if (c.plots.empty()) c.plots.push_back(PlotSpec{});
}

}  // namespace

SweepConfig parse_sweep_config(const std::string& text, const std::string& source_name,
                               const std::string& base_dir) {
  Src src{source_name};
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    throw ConfigError(source_name + ":" + std::to_string(e.source().begin.line) +
                      ": TOML syntax error: " + std::string(e.description()));
  }
  check_keys(root, {"sweep", "scene", "technique", "table", "plot"}, src, "the top level");
  SweepConfig c;
  c.source = source_name;
  c.text = text;
  c.base_dir = base_dir;
  json canon;

  parse_sweep_table(root, src, c);
  parse_cost_model(root.get("sweep") ? root.get("sweep")->as_table() : nullptr, src, base_dir, c);

  // [[scene]]: parsed, then completed from its files (sizes, proportions, hashes).
  const toml::array* scenes = root.get("scene") ? root.get("scene")->as_array() : nullptr;
  if (!scenes || scenes->empty()) fail(source_name, "no [[scene]] given");
  std::set<std::string> scene_names;
  for (const toml::node& n : *scenes) {
    const toml::table* t = n.as_table();
    if (!t) fail(src.at(n), "[[scene]] must be a table");
    add_scene(c, canon, scene_names, *t, n, src, base_dir);
  }

  // [[technique]]
  const toml::array* techniques =
      root.get("technique") ? root.get("technique")->as_array() : nullptr;
  if (!techniques || techniques->empty()) fail(source_name, "no [[technique]] given");
  for (const toml::node& n : *techniques) {
    const toml::table* t = n.as_table();
    if (!t) fail(src.at(n), "[[technique]] must be a table");
    TechniqueSweep ts = parse_technique(*t, src, n);
    check_technique_sweep(ts, c.scenes);
    c.techniques.push_back(ts);
  }

  // [[table]] and [[plot]]: what is written from the rows.
  const std::set<std::string> fields = sweep_fields();
  parse_tables(root, src, fields, c);
  parse_plots(root, src, fields, c);

  canon["frames"] = c.frames;
  canon["warmup"] = c.warmup;
  canon["truth_tolerance"] = c.truth_tolerance;
  if (c.footprint_samples > 1) {
    // The footprint's truth traces samples^2 rays a pixel; its reference AO would multiply that
    // by the hemisphere's.
    for (const SceneDesc& s : c.scenes)
      if (s.effects.has(Effect::AmbientOcclusion))
        fail(src.at(*root.get("sweep")->as_table()->get("footprint_samples")),
             "'footprint_samples' traces the truth samples^2 times a pixel: scene '" + s.name +
                 "' asks for ambient_occlusion, whose reference would cost that many times its "
                 "hemisphere rays; measure footprints on scenes without it");
    canon["footprint_samples"] = c.footprint_samples;  // absent at 1: older sweeps hash alike
  }
  // A derived column: absent for the default model, so that choosing it keeps every key.
  if (c.cost_model_name != kDefaultCostModel) canon["cost_model"] = c.cost_model_name;
  if (c.op_count_stride != SweepConfig{}.op_count_stride)
    canon["op_count_stride"] = c.op_count_stride;
  c.canonical = canon.dump();
  return c;
}

SweepConfig load_sweep_config(const std::string& path) {
  if (!fs::exists(path)) throw ConfigError(path + ": config file not found");
  if (fs::is_directory(path))
    throw ConfigError(path + ": is a folder; give a sweep config file (.toml), e.g. " +
                      (fs::path(path) / "sweep.toml").string());
  if (!fs::is_regular_file(path))
    throw ConfigError(path +
                      ": is not a regular file (a device, FIFO or socket); give a sweep "
                      "config file (.toml)");
  // A config is a page of text: a huge file is not one (and would be echoed in messages).
  if (fs::file_size(path) > (1u << 20))
    throw ConfigError(path + ": is " + std::to_string(fs::file_size(path)) +
                      " bytes; a sweep config is at most 1 MiB");
  const std::string text = read_text(path, 1u << 20);  // a read error is named, not taken as EOF
  std::string dir = fs::absolute(path).parent_path().string();
  return parse_sweep_config(text, path, dir);
}

const std::vector<std::string>& run_owned_names() {
  static const std::vector<std::string> names = {"results.sqlite",
                                                 "results.sqlite-journal",
                                                 "results.sqlite-wal",
                                                 "results.sqlite-shm",
                                                 "rows.csv",
                                                 "sweep.json",
                                                 "outputs.json",
                                                 ".relieflab-lock",
                                                 "run.log",
                                                 "pareto.md",
                                                 "report.html",
                                                 "report_assets",
                                                 "images",
                                                 "plots",
                                                 "gbuffers"};
  return names;
}

SweepConfig default_sweep_config() {
  const auto& files = embedded_files();
  auto it = files.find("configs/default.toml");
  if (it == files.end()) throw ConfigError("built-in default config missing from the build");
  return parse_sweep_config(it->second, "<built-in configs/default.toml>",
                            data_root() + "/configs");
}

}  // namespace rl
