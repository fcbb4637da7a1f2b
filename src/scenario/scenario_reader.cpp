// SPDX-License-Identifier: GPL-3.0-or-later
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "common/did_you_mean.hpp"
#include "common/errors.hpp"
#include "common/number_text.hpp"
#include "scenario/scenario.hpp"
#include "scenario/scenario_table.hpp"
#include "scenario/toml_text_guard.hpp"
#include "scenario/trajectory_reader.hpp"

namespace roifem::scenario {

namespace {

/// Reads one TOML table strictly: every key must be asked for by name, and close() rejects the
/// rest. Messages carry "file:line:column" and the table's name.
class StrictTable {
 public:
  StrictTable(const toml::table& table, std::string source, std::string name)
      : table_(table), source_(std::move(source)), name_(std::move(name)) {}

  std::string where(const toml::node& node) const { return at(node.source().begin); }
  /// "file:line:column", or the source alone for a table built in memory (no positions).
  std::string at(const toml::source_position& p) const {
    return p.line > 0 ? source_ + ":" + std::to_string(p.line) + ":" + std::to_string(p.column) : source_;
  }
  std::string key_name(const std::string& key) const { return name_.empty() ? key : name_ + "." + key; }
  const toml::node* find(const std::string& key) {
    known_.insert(key);
    return table_.get(key);
  }
  /// "file:line" of the table (its header, or the file for the top level).
  std::string table_where() const {
    const auto line = table_.source().begin.line;
    return line > 0 && !name_.empty() ? source_ + ":" + std::to_string(line) : source_;
  }
  /// A missing required key, naming where its table starts and a present key that looks like a typo of it.
  [[noreturn]] void missing(const std::string& key, const std::string& what = "") const {
    std::string typo;
    for (const auto& [k, node] : table_) {
      const std::string present(k.str());
      if (known_.count(present) || closest_name(present, {key}).empty()) continue;
      const auto line = k.source().begin.line;
      typo = "; '" + present + "'" + (line > 0 ? " at line " + std::to_string(line) : "") + " looks like a misspelling of it";
      break;
    }
    throw InputError(table_where() + ": missing required key '" + key_name(key) + "'" + what + typo);
  }
  [[noreturn]] void wrong(const toml::node& node, const std::string& key, const std::string& what) const {
    throw InputError(where(node) + ": key '" + key_name(key) + "' " + what);
  }

  std::optional<double> number(const std::string& key) {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    std::optional<double> v = node->value<double>();  // integers convert too
    if (!node->is_number() || !v) wrong(*node, key, "must be a number");
    if (!std::isfinite(*v)) wrong(*node, key, "must be finite (got " + std::to_string(*v) + ")");
    return v;
  }
  double number(const std::string& key, double fallback) { return number(key).value_or(fallback); }
  double required_number(const std::string& key) {
    auto v = number(key);
    if (!v) missing(key);
    return *v;
  }
  std::optional<long> integer(const std::string& key) {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_integer()) wrong(*node, key, "must be an integer");
    return static_cast<long>(*node->value<int64_t>());
  }
  std::optional<std::string> string(const std::string& key) {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_string()) wrong(*node, key, "must be a string");
    return *node->value<std::string>();
  }
  std::optional<Vec3> vec3(const std::string& key) {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    const toml::array* a = node->as_array();
    if (!a || a->size() != 3) wrong(*node, key, "must be an array of three numbers");
    Vec3 v;
    for (std::size_t i = 0; i < 3; ++i) {
      const auto x = (*a)[i].value<double>();
      if (!(*a)[i].is_number() || !x) wrong(*node, key, "must be an array of three numbers");
      if (!std::isfinite(*x)) wrong(*node, key, "must hold finite numbers");
      v[static_cast<Index>(i)] = *x;
    }
    return v;
  }
  /// An array of one or more finite numbers.
  std::optional<std::vector<double>> numbers(const std::string& key) {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    const toml::array* a = node->as_array();
    if (!a || a->empty()) wrong(*node, key, "must be an array of one or more numbers");
    std::vector<double> out;
    for (const auto& item : *a) {
      const auto x = item.value<double>();
      if (!item.is_number() || !x) wrong(*node, key, "must be an array of one or more numbers");
      if (!std::isfinite(*x)) wrong(*node, key, "must hold finite numbers");
      out.push_back(*x);
    }
    return out;
  }
  std::vector<std::string> strings(const std::string& key) {
    const toml::node* node = find(key);
    if (!node) return {};
    const toml::array* a = node->as_array();
    if (!a) wrong(*node, key, "must be an array of strings");
    std::vector<std::string> out;
    for (const auto& item : *a) {
      if (!item.is_string()) wrong(*node, key, "must be an array of strings");
      out.push_back(*item.value<std::string>());
    }
    return out;
  }
  const toml::table* subtable(const std::string& key) {
    const toml::node* node = find(key);
    if (!node) return nullptr;
    if (!node->is_table()) wrong(*node, key, "must be a table [" + key_name(key) + "]");
    return node->as_table();
  }
  const toml::array* table_array(const std::string& key) {
    const toml::node* node = find(key);
    if (!node) return nullptr;
    if (!node->is_array_of_tables()) wrong(*node, key, "must be an array of tables [[" + key_name(key) + "]]");
    return node->as_array();
  }
  /// Rejects every key that was not asked for, listing the valid ones.
  void close() const {
    for (const auto& [key, node] : table_) {
      (void)node;
      const std::string k(key.str());
      if (known_.count(k)) continue;
      std::string valid;
      for (const auto& name : known_) valid += (valid.empty() ? "" : ", ") + name;
      const std::string hint = did_you_mean(k, std::vector<std::string>(known_.begin(), known_.end()));
      // the key's own position, not its value's
      throw InputError(at(key.source().begin) + ": unknown key '" + key_name(k) + "'" + hint +
                       (valid.empty() ? "" : " (valid: " + valid + ")"));
    }
  }
  const std::string& source() const { return source_; }

 private:
  const toml::table& table_;
  std::string source_, name_;
  std::set<std::string> known_;
};

/// The keys a [material] or [[material_region]] table may give.
struct MaterialKeys {
  std::optional<std::string> preset, model;
  std::optional<double> lambda, mu, young, poisson, rho, alpha;
  std::optional<std::vector<double>> ogden_mu, ogden_alpha;  ///< the Ogden law's terms
  bool elastic() const { return lambda || mu || young || poisson || ogden_mu; }
  bool any() const { return elastic() || rho || alpha || ogden_alpha; }
};

MaterialKeys read_material_keys(StrictTable& t) {
  MaterialKeys k{.preset = t.string("preset"),
                 .model = t.string("model"),
                 .lambda = t.number("lambda_Pa"),
                 .mu = t.number("mu_Pa"),
                 .young = t.number("young_Pa"),
                 .poisson = t.number("poisson"),
                 .rho = t.number("rho_kg_m3"),
                 .alpha = t.number("alpha_per_s"),
                 .ogden_mu = t.numbers("ogden_mu_Pa"),
                 .ogden_alpha = t.numbers("ogden_alpha")};
  return k;
}

/// The Ogden keys merged into `m` (its model already merged): ogden_alpha gives the terms, and
/// ogden_mu_Pa their moduli, whose sum replaces mu (lambda, or poisson, still gives the bulk
/// modulus); one term without ogden_mu_Pa takes mu. A term's mu_i or alpha_i outside its domain,
/// and terms given to another law, are refused by Material::validate.
void merge_ogden_terms(fem::Material& m, const MaterialKeys& k) {
  if (k.ogden_mu && !k.ogden_alpha) throw InputError("gives ogden_mu_Pa without ogden_alpha (the Ogden law's exponents)");
  if (!k.ogden_alpha) {
    if (m.model != fem::MaterialModel::ogden) m.ogden.clear();
    if (m.ogden.size() == 1) m.ogden[0].mu = m.mu;  // one term follows the shear modulus a region gives
    return;
  }
  if (k.ogden_mu && k.ogden_mu->size() != k.ogden_alpha->size())
    throw InputError("gives " + std::to_string(k.ogden_mu->size()) + " ogden_mu_Pa value(s) and " +
                     std::to_string(k.ogden_alpha->size()) + " ogden_alpha value(s); give one of each per term");
  if (!k.ogden_mu && k.ogden_alpha->size() > 1)
    throw InputError("gives " + std::to_string(k.ogden_alpha->size()) +
                     " ogden_alpha values and no ogden_mu_Pa; give each term's mu_i (only one term takes mu)");
  m.ogden.clear();
  double sum = 0;
  for (std::size_t i = 0; i < k.ogden_alpha->size(); ++i) {
    const double mu_i = k.ogden_mu ? (*k.ogden_mu)[i] : m.mu;
    m.ogden.push_back({.mu = mu_i, .alpha = (*k.ogden_alpha)[i]});
    sum += mu_i;
  }
  if (!k.ogden_mu) return;
  if (k.mu || k.young)
    throw InputError(
        "gives ogden_mu_Pa and " + std::string(k.mu ? "mu_Pa" : "young_Pa") +
        "; the Ogden law's shear modulus is the sum of ogden_mu_Pa (give lambda_Pa or poisson for its bulk modulus)");
  if (k.poisson && !k.young) {
    const double nu = *k.poisson;
    if (!(nu > -1.0 && nu < 0.5))
      throw InputError("material: Poisson's ratio nu = " + number_text(nu) + " must lie in (-1, 0.5)");
    m.lambda = 2 * sum * nu / (1 - 2 * nu);
  }
  m.mu = sum;
}

/// `start` with the keys given merged in (the elastic pair given, lambda/mu or E/nu, replaces the
/// other's), validated.
fem::Material merged_material(fem::Material m, const MaterialKeys& k) {
  if ((k.lambda || k.mu) && (k.young || k.poisson))
    throw InputError("gives both lambda_Pa/mu_Pa and young_Pa/poisson; give one pair");
  if (k.ogden_mu) {  // the shear modulus is their sum: lambda_Pa or poisson alone give the bulk (merge_ogden_terms)
    m.lambda = k.lambda.value_or(m.lambda);
  } else if (k.lambda || k.mu) {
    m.lambda = k.lambda.value_or(m.lambda);
    m.mu = k.mu.value_or(m.mu);
  }
  if (!k.ogden_mu && (k.young || k.poisson)) {
    const fem::Material elastic =
        fem::Material::from_young_poisson(k.young.value_or(m.young()), k.poisson.value_or(m.poisson()), 1.0, 0.0);
    m.lambda = elastic.lambda;
    m.mu = elastic.mu;
  }
  m.rho = k.rho.value_or(m.rho);
  m.alpha = k.alpha.value_or(m.alpha);
  if (k.model) m.model = fem::parse_material_model(*k.model);
  merge_ogden_terms(m, k);
  if (m.model == fem::MaterialModel::ogden && m.ogden.empty())
    throw InputError(
        "model = \"ogden\" needs ogden_alpha (the exponents; brain tissue about -20) and, for more than one "
        "term, ogden_mu_Pa");
  m.validate();
  return m;
}

fem::Material read_material_values(StrictTable& t, std::string& name) {
  const MaterialKeys k = read_material_keys(t);
  t.close();
  if (k.preset) {
    name = k.any() ? *k.preset + " (modified)" : *k.preset;
    return merged_material(fem::material_preset(*k.preset), k);
  }
  name = "custom";
  if ((k.lambda || k.mu) && (k.young || k.poisson)) return merged_material({}, k);  // names the clash
  if (!((k.lambda && k.mu) || (k.young && k.poisson) || (k.ogden_mu && (k.lambda || k.poisson))))
    throw InputError(t.source() +
                     ": [material] needs 'preset', or lambda_Pa and mu_Pa, or young_Pa and poisson (the Ogden law: ogden_mu_Pa "
                     "with lambda_Pa or poisson)");
  if (!k.rho) throw InputError(t.source() + ": missing required key 'material.rho_kg_m3'");
  if (!k.alpha) throw InputError(t.source() + ": missing required key 'material.alpha_per_s'");
  return merged_material({}, k);
}

/// The material table; a non-physical value is reported with the file's name.
fem::Material read_material(StrictTable& t, std::string& name) {
  try {
    return read_material_values(t, name);
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (message.rfind(t.source(), 0) == 0) throw;
    throw InputError(t.source() + ": [material] " + message);
  }
}

/// A [[material_region]]: a 3D set and the material its tetrahedra take.
fem::RegionMaterial read_region_material(StrictTable& t, const fem::Material& base) {
  const auto set = t.string("set");
  const MaterialKeys k = read_material_keys(t);
  t.close();
  if (!set) t.missing("set", " (the named volume set, e.g. white_matter)");
  fem::RegionMaterial region{.set = *set, .material = {}, .name = k.preset.value_or("custom")};
  try {
    // Keys left out keep the brain's ([material]); a preset starts from the preset instead. A
    // region keeps the brain's law unless it names its own, by model or by a measured tissue's
    // preset (cortex, ...: an Ogden law).
    fem::Material start = k.preset ? fem::material_preset(*k.preset) : base;
    if (start.model == fem::MaterialModel::linear) {
      start.model = base.model;
      start.ogden = base.ogden;
    }
    region.material = merged_material(start, k);
  } catch (const InputError& e) {
    throw InputError(t.source() + ": [[material_region]] '" + region.set + "': " + e.what());
  }
  return region;
}

condensation::Reduction read_reduction(StrictTable& t) {
  condensation::Reduction r;
  const std::string kind = t.string("reduction").value_or("static");
  const auto table = condensation::reduction_table();
  const auto row = std::find_if(table.begin(), table.end(), [&](const auto& info) { return info.key == kind; });
  if (row == table.end()) {
    std::vector<std::string> keys;
    for (const auto& info : table) keys.emplace_back(info.key);
    throw InputError(t.source() + ": key 'roi.reduction' must be one of " + condensation::reduction_key_list() + " (got '" +
                     kind + "')" + did_you_mean(kind, keys));
  }
  r.kind = &*row;
  const auto modes = t.integer("modes");
  const double cutoff = t.number("cutoff_rad_s", 0.0);
  const std::string named = "reduction = \"" + kind + "\"";
  if (!row->counted) {
    if (modes || cutoff != 0)
      throw InputError(t.source() + ": keys 'roi.modes' and 'roi.cutoff_rad_s' belong to reduction = " +
                       condensation::quoted_keys(&condensation::ReductionInfo::counted));
    return r;
  }
  if (cutoff != 0 && !row->takes_cutoff)
    throw InputError(t.source() + ": key 'roi.cutoff_rad_s' belongs to reduction = " +
                     condensation::quoted_keys(&condensation::ReductionInfo::takes_cutoff));
  if (modes && *modes <= 0)
    throw InputError(t.source() + ": key 'roi.modes' must be positive (got " + std::to_string(*modes) + ")");
  if (cutoff < 0) throw InputError(t.source() + ": key 'roi.cutoff_rad_s' must be positive");
  if (!modes && !(cutoff > 0))
    throw InputError(t.source() + ": " + named +
                     (row->takes_cutoff ? " needs key 'roi.modes' or 'roi.cutoff_rad_s'" : " needs a positive key 'roi.modes'"));
  r.modes = modes.value_or(0);
  r.cutoff_rad_s = modes ? 0.0 : cutoff;
  return r;
}

roi::RoiSpec read_roi(StrictTable& t) {
  roi::RoiSpec spec;
  const std::string kind = t.string("kind").value_or("");
  if (kind == "all") {
    spec.kind = roi::RoiSpec::Kind::all;
  } else if (kind == "ball") {
    spec.kind = roi::RoiSpec::Kind::ball;
    spec.center = t.vec3("center_mm").value_or(Vec3::Constant(NAN)) * mm;
    spec.radius = t.number("radius_mm", NAN) * mm;
    if (!spec.center.allFinite()) t.missing("center_mm");
    if (std::isnan(spec.radius)) t.missing("radius_mm", " (the ball's radius in mm)");
    if (!(spec.radius > 0)) throw InputError(t.source() + ": key 'roi.radius_mm' must be positive");
  } else if (kind == "nearest") {
    spec.kind = roi::RoiSpec::Kind::nearest;
    spec.center = t.vec3("target_mm").value_or(Vec3::Constant(NAN)) * mm;
    if (!spec.center.allFinite()) t.missing("target_mm");
    const auto count = t.integer("nodes");
    if (!count) t.missing("nodes");
    if (*count <= 0) throw InputError(t.source() + ": key 'roi.nodes' must be positive (got " + std::to_string(*count) + ")");
    spec.count = *count;
  } else if (kind == "set") {
    spec.kind = roi::RoiSpec::Kind::set;
    const auto set = t.string("set");
    if (!set) t.missing("set");
    spec.set = *set;
  } else {
    throw InputError(t.source() + ": key 'roi.kind' must be one of all, ball, nearest, set (got '" + kind + "')");
  }
  t.close();
  return spec;
}

/// ramp_s (>= 0) and ramp_shape ("linear", the default, or "smooth").
model::Ramp read_ramp(StrictTable& t, const toml::node& node) {
  model::Ramp ramp;
  ramp.duration = t.number("ramp_s", 0.0);
  if (ramp.duration < 0) throw InputError(t.where(node) + ": key '" + t.key_name("ramp_s") + "' must be >= 0");
  const std::string shape = t.string("ramp_shape").value_or("linear");
  if (shape == "smooth")
    ramp.shape = model::Ramp::Shape::smooth;
  else if (shape != "linear")
    throw InputError(t.where(node) + ": key '" + t.key_name("ramp_shape") + "' must be \"linear\" or \"smooth\" (got '" + shape +
                     "')" + did_you_mean(shape, {"linear", "smooth"}));
  return ramp;
}

std::string ramp_toml(const model::Ramp& ramp);

/// A tool's name names its group of results.h5 (/tools/NAME): a word, not a path, and not the
/// name of a dataset beside the tools' groups.
void check_tool_name(const std::string& name, const std::string& where) {
  const bool word = !name.empty() && name.front() != '.' && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (!word)
    throw InputError(where + ": key 'tool.name' = '" + name +
                     "' is not a name: letters, digits, '_', '-' and '.' (not first) only, since it names the tool's group "
                     "/tools/NAME of results.h5");
  if (name == "position_drift_mm")
    throw InputError(where + ": key 'tool.name' = '" + name + "' is taken by results.h5's dataset /tools/position_drift_mm");
}

/// A [[tool]]: a name, where it holds (set, or center_mm and radius_mm) and its path.
model::SetTool read_tool(StrictTable t, const toml::node& node, const std::vector<model::SetTool>& earlier,
                         const std::filesystem::path& directory) {
  model::SetTool tool;
  tool.where = t.table_where();
  tool.name = t.string("name").value_or("tool" + std::to_string(earlier.size() + 1));
  if (const toml::node* name = t.find("name")) check_tool_name(tool.name, t.where(*name));
  for (const auto& other : earlier)
    if (other.name == tool.name) throw InputError(t.where(node) + ": two [[tool]] tables are named '" + tool.name + "'");
  const auto set = t.string("set");
  const auto center = t.vec3("center_mm");
  const auto radius = t.number("radius_mm");
  if (set && (center || radius))
    throw InputError(t.where(node) + ": a [[tool]] holds a set or the boundary nodes within center_mm and radius_mm, not both");
  if (set) {
    tool.set = *set;
  } else {
    if (!center) t.missing("set", " (or center_mm and radius_mm)");
    if (!radius) t.missing("radius_mm");
    if (!(*radius > 0))
      throw InputError(t.where(node) + ": key 'tool.radius_mm' must be positive (got " + number_text(*radius) + ")");
    tool.center = *center * mm;
    tool.radius = *radius * mm;
  }
  const auto displacement = t.vec3("displacement_mm");
  if (const auto file = t.string("trajectory")) {
    if (displacement || t.number("ramp_s") || t.string("ramp_shape"))
      throw InputError(t.where(node) + ": a [[tool]] follows a trajectory or displacement_mm over a ramp, not both");
    try {
      tool.path = read_trajectory(std::filesystem::path(*file).is_absolute() ? std::filesystem::path(*file) : directory / *file);
    } catch (const InputError& e) {  // the file's own line where it has one, after the scenario's
      throw InputError(t.where(*t.find("trajectory")) + ": key 'tool.trajectory': " + e.what());
    }
  } else {
    if (!displacement) t.missing("displacement_mm", " (or trajectory)");
    tool.path.displacement = *displacement * mm;
    tool.path.ramp = read_ramp(t, node);
  }
  t.close();
  return tool;
}

/// A [[cut]]: its blade's edge, start and path (a straight move over a time, or a trajectory).
cutting::Blade read_cut(StrictTable t, const toml::node& node, const std::vector<cutting::Blade>& earlier,
                        const std::filesystem::path& directory) {
  cutting::Blade blade;
  blade.where = t.table_where();
  blade.name = t.string("name").value_or("cut" + std::to_string(earlier.size() + 1));
  for (const auto& other : earlier)
    if (other.name == blade.name) throw InputError(t.where(node) + ": two [[cut]] tables are named '" + blade.name + "'");
  const std::string mode = t.string("mode").value_or("remove");
  if (mode != "remove" && mode != "split")
    throw InputError(t.where(*t.find("mode")) + ": key 'cut.mode' must be \"remove\" or \"split\" (got '" + mode + "')" +
                     did_you_mean(mode, {"remove", "split"}));
  blade.mode = mode == "split" ? cutting::CutMode::split : cutting::CutMode::remove;
  for (const auto& other : earlier)
    if (other.mode != blade.mode)
      throw InputError(t.where(t.find("mode") ? *t.find("mode") : node) + ": " + blade.describe() + " is in " + mode +
                       " mode and " + other.describe() + " is not: a scenario's cuts share one mode (remove or split)");
  const auto from = t.vec3("edge_from_mm");
  const auto to = t.vec3("edge_to_mm");
  if (!from) t.missing("edge_from_mm");
  if (!to) t.missing("edge_to_mm");
  if (*from == *to)
    throw InputError(t.where(*t.find("edge_to_mm")) +
                     ": key 'cut.edge_to_mm' equals 'cut.edge_from_mm': the blade's edge has no length and cuts nothing");
  blade.edge_a = *from * mm;
  blade.edge_b = *to * mm;
  blade.start = t.number("start_s", 0.0);
  if (blade.start < 0)
    throw InputError(t.where(*t.find("start_s")) + ": key 'cut.start_s' must be >= 0 (got " + number_text(blade.start) + ")");
  const auto move = t.vec3("move_mm");
  if (const auto file = t.string("trajectory")) {
    if (move || t.number("duration_s"))
      throw InputError(t.where(node) + ": a [[cut]] follows a trajectory or move_mm over duration_s, not both");
    try {
      blade.path = read_trajectory(std::filesystem::path(*file).is_absolute() ? std::filesystem::path(*file) : directory / *file);
    } catch (const InputError& e) {
      throw InputError(t.where(*t.find("trajectory")) + ": key 'cut.trajectory': " + e.what());
    }
  } else {
    if (!move) t.missing("move_mm", " (or trajectory)");
    const auto duration = t.number("duration_s");
    if (!duration) t.missing("duration_s");
    if (!(*duration > 0))
      throw InputError(t.where(*t.find("duration_s")) + ": key 'cut.duration_s' must be positive (got " + number_text(*duration) +
                       "): a blade moves at a finite speed");
    if (move->norm() == 0)
      throw InputError(t.where(*t.find("move_mm")) + ": key 'cut.move_mm' is zero: a blade that does not move sweeps nothing");
    blade.path.displacement = *move * mm;
    blade.path.ramp.duration = *duration;
  }
  t.close();
  return blade;
}

std::string toml_number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  std::string out = s.str();
  if (out.find_first_of(".eEn") == std::string::npos) out += ".0";
  return out;
}

std::string ramp_toml(const model::Ramp& ramp) {
  return "ramp_s = " + toml_number(ramp.duration) + "\n" +
         (ramp.shape == model::Ramp::Shape::smooth ? "ramp_shape = \"smooth\"\n" : "");
}

}  // namespace

toml::table parse_scenario_table(std::string_view text, const std::string& source) {
  check_toml_text(text, source);
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw InputError(source + ":" + std::to_string(b.line) + ":" + std::to_string(b.column) +
                     ": TOML syntax error: " + std::string(e.description()));
  }
}

std::string read_scenario_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot open scenario file");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

Scenario parse_scenario(std::string_view text, const std::string& source, const std::filesystem::path& directory) {
  return scenario_from_table(parse_scenario_table(text, source), source, directory);
}

Scenario scenario_from_table(const toml::table& root, const std::string& source, const std::filesystem::path& directory) {
  Scenario s;
  s.file = source;
  StrictTable top(root, source, "");
  const auto mesh = top.string("mesh");
  if (!mesh) top.missing("mesh");
  s.mesh = std::filesystem::path(*mesh).is_absolute() ? std::filesystem::path(*mesh) : directory / *mesh;
  if (const auto element = top.string("element")) {
    try {
      s.element = fem::parse_element(*element);
    } catch (const InputError& e) {
      throw InputError(source + ": key 'element': " + e.what());
    }
  }

  if (const toml::table* t = top.subtable("material")) {
    StrictTable material(*t, source, "material");
    s.material = read_material(material, s.material_name);
  } else {
    s.material = fem::material_preset(s.material_name);
  }
  if (const toml::array* regions = top.table_array("material_region"))
    for (const auto& node : *regions) {
      StrictTable region(*node.as_table(), source, "material_region");
      s.material_regions.push_back(read_region_material(region, s.material));
    }
  if (const toml::table* t = top.subtable("boundary")) {
    StrictTable boundary(*t, source, "boundary");
    s.fixed_sets = boundary.strings("fixed");
    boundary.close();
  }
  if (const toml::array* loads = top.table_array("load")) {
    for (const auto& node : *loads) {
      StrictTable load(*node.as_table(), source, "load");
      model::SetLoad l;
      const auto set = load.string("set");
      const auto force = load.vec3("force_N");
      l.gravity = load.vec3("gravity_m_s2");
      if (l.gravity && (set || force))
        throw InputError(load.where(node) + ": a [[load]] is either gravity_m_s2 or set and force_N, not both");
      if (!l.gravity) {
        if (!set) load.missing("set");
        if (!force) load.missing("force_N");
        l.set = *set;
        l.force = *force;
      }
      l.ramp = read_ramp(load, node);
      load.close();
      s.loads.push_back(l);
    }
  }
  if (const toml::array* tools = top.table_array("tool"))
    for (const auto& node : *tools)
      s.tools.push_back(read_tool(StrictTable(*node.as_table(), source, "tool"), node, s.tools, directory));
  if (const toml::array* cuts = top.table_array("cut"))
    for (const auto& node : *cuts)
      s.cuts.push_back(read_cut(StrictTable(*node.as_table(), source, "cut"), node, s.cuts, directory));
  if (const toml::table* t = top.subtable("roi")) {
    StrictTable roi_table(*t, source, "roi");
    s.reduction = read_reduction(roi_table);
    s.roi = read_roi(roi_table);
  }
  if (const toml::table* t = top.subtable("time")) {
    StrictTable time(*t, source, "time");
    s.integrator = time.string("integrator").value_or(s.integrator);
    if (const toml::node* integrator = time.find("integrator")) s.integrator_where = time.where(*integrator);
    s.dt = time.number("dt_s", s.dt);
    s.steps = time.integer("steps").value_or(s.steps);
    s.rtol = time.number("rtol");
    s.atol = time.number("atol");
    time.close();
    if (s.rtol && !(*s.rtol > 0 && *s.rtol < 1))
      throw InputError(source + ": key 'time.rtol' must lie in (0, 1) (got " + number_text(*s.rtol) + ")");
    if (s.atol && !(*s.atol > 0))
      throw InputError(source + ": key 'time.atol' must be positive (got " + number_text(*s.atol) + ")");
    if (s.atol && !s.rtol) throw InputError(source + ": key 'time.atol' needs key 'time.rtol' (error-controlled steps)");
    if (!(s.dt > 0)) throw InputError(source + ": key 'time.dt_s' must be positive (got " + number_text(s.dt) + ")");
    if (s.dt < scenario::Scenario::smallest_dt)
      throw InputError(source + ": key 'time.dt_s' = " + number_text(s.dt) + " s is below " +
                       number_text(scenario::Scenario::smallest_dt) +
                       " s, where 4/dt^2 M swamps K in the effective stiffness and the steps mean nothing");
    if (s.steps <= 0) throw InputError(source + ": key 'time.steps' must be positive (got " + std::to_string(s.steps) + ")");
  }
  s.reduction = s.reduction.trained_on(s.dt, s.steps);
  const double t_end = s.dt * static_cast<double>(s.steps);
  for (const auto& cut : s.cuts)
    if (cut.start >= t_end)
      throw InputError(cut.where + ": " + cut.describe() + " starts at t = " + number_text(cut.start) + " s, when the run (" +
                       std::to_string(s.steps) + " steps of " + number_text(s.dt) + " s) has ended at t = " + number_text(t_end) +
                       " s");  // a POD basis learns from the run's own step and length
  if (const toml::table* t = top.subtable("haptic")) {
    StrictTable haptic(*t, source, "haptic");
    s.haptic_rate_hz = haptic.number("rate_hz");
    const auto iterations = haptic.integer("newton_iterations");
    haptic.close();
    if (s.haptic_rate_hz && !(*s.haptic_rate_hz > 0 && *s.haptic_rate_hz <= 100000))
      throw InputError(source + ": key 'haptic.rate_hz' must lie in (0, 100000] (got " + number_text(*s.haptic_rate_hz) + ")");
    if (iterations && (*iterations < 1 || *iterations > 1000))
      throw InputError(source + ": key 'haptic.newton_iterations' must lie in [1, 1000] (got " + std::to_string(*iterations) +
                       ")");
    if (iterations) s.haptic_newton_iterations = static_cast<int>(*iterations);
  }
  if (const toml::table* t = top.subtable("restart")) {
    StrictTable restart(*t, source, "restart");
    const auto from = restart.string("from");
    const auto step = restart.integer("step");
    if (!from) restart.missing("from");
    s.restart =
        Scenario::Restart{.from = std::filesystem::path(*from).is_absolute() ? std::filesystem::path(*from) : directory / *from,
                          .step = step,
                          .where = restart.where(*t)};
    restart.close();
    if (step && *step < 0)
      throw InputError(source + ": key 'restart.step' must be 0 or more (got " + std::to_string(*step) + ")");
  }
  if (const toml::table* t = top.subtable("output")) {
    StrictTable output(*t, source, "output");
    s.field_every = output.integer("field_every").value_or(s.field_every);
    s.restart_every = output.integer("restart_every");
    if (s.restart_every && *s.restart_every < 0)
      throw InputError(source + ": key 'output.restart_every' must be >= 0 (got " + std::to_string(*s.restart_every) + ")");
    output.close();
    if (s.field_every < 0) throw InputError(source + ": key 'output.field_every' must be >= 0");
  }
  top.close();
  return s;
}

void refuse_run_only_tables(const Scenario& scenario, std::string_view command) {
  if (scenario.restart)
    throw InputError((scenario.restart->where.empty() ? scenario.file.string() : scenario.restart->where) + ": [restart]: " +
                     std::string(command) + " starts from rest and does not go on an earlier run; `roifem run` does");
  if (scenario.cuts.empty()) return;
  const cutting::Blade& first = scenario.cuts.front();
  throw InputError((first.where.empty() ? scenario.file.string() : first.where) + ": [[cut]] '" + first.name + "' (" +
                   std::to_string(scenario.cuts.size()) + " cut(s) in all): " + std::string(command) +
                   " does not take cuts and would measure the uncut model; `roifem run` takes them (remove the [[cut]] "
                   "tables to study the uncut model)");
}

Scenario read_scenario(const std::filesystem::path& file) {
  return parse_scenario(read_scenario_text(file), file.string(), file.parent_path());
}

namespace {

std::string toml_numbers(const std::vector<fem::OgdenTerm>& terms, double fem::OgdenTerm::*field) {
  std::string out = "[";
  for (std::size_t i = 0; i < terms.size(); ++i) out += (i ? ", " : "") + toml_number(terms[i].*field);
  return out + "]";
}

/// A material's keys, each line after a newline, as the reader reads them back to the same
/// material (the model's line where `with_model`): one Ogden term takes mu_Pa; more give
/// ogden_mu_Pa in its place.
std::string material_toml(const fem::Material& m, bool with_model) {
  std::ostringstream o;
  o << "\nlambda_Pa = " << toml_number(m.lambda);
  if (m.ogden.size() > 1)
    o << "\nogden_mu_Pa = " << toml_numbers(m.ogden, &fem::OgdenTerm::mu);
  else
    o << "\nmu_Pa = " << toml_number(m.mu);
  o << "\nrho_kg_m3 = " << toml_number(m.rho) << "\nalpha_per_s = " << toml_number(m.alpha) << "\n";
  if (with_model) o << "model = \"" << fem::material_model_name(m.model) << "\"\n";
  if (!m.ogden.empty()) o << "ogden_alpha = " << toml_numbers(m.ogden, &fem::OgdenTerm::alpha) << "\n";
  return o.str();
}

}  // namespace

std::string Scenario::resolved_toml() const {
  std::ostringstream o;
  o << "mesh = \"" << mesh.string() << "\"\nelement = \"" << fem::element_name(element) << "\"\n\n[material]  # " << material_name
    << material_toml(material, material.model != fem::MaterialModel::linear);
  for (const auto& r : material_regions)
    o << "\n[[material_region]]  # " << r.name << "\nset = \"" << r.set << "\""
      << material_toml(r.material, r.material.model != material.model);
  o << "\n[boundary]\nfixed = [";
  for (std::size_t i = 0; i < fixed_sets.size(); ++i) o << (i ? ", " : "") << '"' << fixed_sets[i] << '"';
  o << "]\n";
  for (const auto& l : loads) {
    if (l.gravity)
      o << "\n[[load]]\ngravity_m_s2 = [" << toml_number(l.gravity->x()) << ", " << toml_number(l.gravity->y()) << ", "
        << toml_number(l.gravity->z()) << "]";
    else
      o << "\n[[load]]\nset = \"" << l.set << "\"\nforce_N = [" << toml_number(l.force.x()) << ", " << toml_number(l.force.y())
        << ", " << toml_number(l.force.z()) << "]";
    o << "\n" << ramp_toml(l.ramp);
  }
  for (const auto& t : tools) {
    o << "\n[[tool]]\nname = \"" << t.name << "\"\n";
    if (t.set.empty())
      o << "center_mm = [" << toml_number(t.center.x() / mm) << ", " << toml_number(t.center.y() / mm) << ", "
        << toml_number(t.center.z() / mm) << "]\nradius_mm = " << toml_number(t.radius / mm) << "\n";
    else
      o << "set = \"" << t.set << "\"\n";
    if (t.path.trajectory)
      o << "trajectory = \"" << t.path.trajectory_file << "\"\n";
    else
      o << "displacement_mm = [" << toml_number(t.path.displacement.x() / mm) << ", " << toml_number(t.path.displacement.y() / mm)
        << ", " << toml_number(t.path.displacement.z() / mm) << "]\n"
        << ramp_toml(t.path.ramp);
  }
  for (const auto& c : cuts) {
    o << "\n[[cut]]\nname = \"" << c.name << "\"\nmode = \"" << (c.mode == cutting::CutMode::split ? "split" : "remove")
      << "\"\nedge_from_mm = [" << toml_number(c.edge_a.x() / mm) << ", " << toml_number(c.edge_a.y() / mm) << ", "
      << toml_number(c.edge_a.z() / mm) << "]\nedge_to_mm = [" << toml_number(c.edge_b.x() / mm) << ", "
      << toml_number(c.edge_b.y() / mm) << ", " << toml_number(c.edge_b.z() / mm) << "]\nstart_s = " << toml_number(c.start)
      << "\n";
    if (c.path.trajectory)
      o << "trajectory = \"" << c.path.trajectory_file << "\"\n";
    else
      o << "move_mm = [" << toml_number(c.path.displacement.x() / mm) << ", " << toml_number(c.path.displacement.y() / mm) << ", "
        << toml_number(c.path.displacement.z() / mm) << "]\nduration_s = " << toml_number(c.path.ramp.duration) << "\n";
  }
  if (roi) {
    o << "\n[roi]\n";
    switch (roi->kind) {
      case roi::RoiSpec::Kind::all:
        o << "kind = \"all\"\n";
        break;
      case roi::RoiSpec::Kind::ball:
        o << "kind = \"ball\"\ncenter_mm = [" << toml_number(roi->center.x() / mm) << ", " << toml_number(roi->center.y() / mm)
          << ", " << toml_number(roi->center.z() / mm) << "]\nradius_mm = " << toml_number(roi->radius / mm) << "\n";
        break;
      case roi::RoiSpec::Kind::nearest:
        o << "kind = \"nearest\"\ntarget_mm = [" << toml_number(roi->center.x() / mm) << ", " << toml_number(roi->center.y() / mm)
          << ", " << toml_number(roi->center.z() / mm) << "]\nnodes = " << roi->count << "\n";
        break;
      case roi::RoiSpec::Kind::set:
        o << "kind = \"set\"\nset = \"" << roi->set << "\"\n";
        break;
    }
    o << "reduction = \"" << reduction.info().key << "\"\n";
    if (reduction.modes > 0)
      o << "modes = " << reduction.modes << "\n";
    else if (reduction.cutoff_rad_s > 0)
      o << "cutoff_rad_s = " << toml_number(reduction.cutoff_rad_s) << "\n";
  }
  o << "\n[time]\nintegrator = \"" << integrator << "\"\ndt_s = " << toml_number(dt) << "\nsteps = " << steps << "\n";
  if (rtol) o << "rtol = " << toml_number(*rtol) << "\natol = " << toml_number(absolute_tolerance()) << "\n";
  if (haptic_rate_hz || haptic_newton_iterations) {
    o << "\n[haptic]\n";
    if (haptic_rate_hz) o << "rate_hz = " << toml_number(*haptic_rate_hz) << "\n";
    if (haptic_newton_iterations) o << "newton_iterations = " << *haptic_newton_iterations << "\n";
  }
  o << "\n[output]\nfield_every = " << field_every << "\n";
  if (restart_every) o << "restart_every = " << *restart_every << "\n";
  return o.str();
}

}  // namespace roifem::scenario
