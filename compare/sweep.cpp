#include "compare/sweep.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>
#include <toml++/toml.h>

namespace ringcrush::compare {
namespace fs = std::filesystem;

std::map<std::string, SweepCaseRunner>& sweep_model_registry() {
  static std::map<std::string, SweepCaseRunner> registry;
  return registry;
}

namespace {

std::string read_text(const fs::path& file, const std::string& what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(file.string(), "", "cannot open the " + what);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string literal(const toml::node& n) {
  if (auto s = n.as_string()) return s->get();
  std::ostringstream out;
  n.visit([&](auto&& v) { out << v; });
  return out.str();
}

// Sets `dotted` (a.b.c) in `root` to `value`, creating intermediate tables.
void set_dotted(toml::table& root, const std::string& dotted, const toml::node& value,
                const std::string& file) {
  toml::table* t = &root;
  std::size_t start = 0;
  for (std::size_t dot; (dot = dotted.find('.', start)) != std::string::npos; start = dot + 1) {
    const std::string part = dotted.substr(start, dot - start);
    if (!t->contains(part)) t->insert(part, toml::table{});
    t = (*t)[part].as_table();
    if (!t) throw SceneError(file, dotted, fmt::format("\"{}\" is not a table in the base scene", part));
  }
  t->insert_or_assign(dotted.substr(start), value);
}

}  // namespace

SweepGrid load_sweep_grid(const fs::path& grid_file) {
  const std::string file = grid_file.string();
  toml::table root;
  try {
    root = toml::parse(read_text(grid_file, "sweep grid"), file);
  } catch (const toml::parse_error& e) {
    throw SceneError(file, fmt::format("line {}", e.source().begin.line),
                     fmt::format("not valid TOML: {}", e.description()));
  }
  SweepGrid g;
  g.source = grid_file;
  for (auto&& [k, v] : root)
    if (k != "base_scene" && k != "model" && k != "axis")
      throw SceneError(file, std::string(k.str()), "unknown key (expected base_scene, model, [[axis]])");
  auto base = root["base_scene"].value<std::string>();
  if (!base) throw SceneError(file, "base_scene", "missing required string");
  g.base_scene = grid_file.parent_path() / *base;
  g.model = root["model"].value_or(std::string("hinge"));
  if (!sweep_model_registry().empty() && !sweep_model_registry().count(g.model)) {
    std::string known;
    for (auto& [name, r] : sweep_model_registry()) known += (known.empty() ? "" : ", ") + name;
    throw SceneError(file, "model", fmt::format("\"{}\" is not one of {}", g.model, known));
  }
  const toml::array* axes = root["axis"].as_array();
  if (!axes || axes->empty()) throw SceneError(file, "axis", "at least one [[axis]] table is required");

  std::vector<std::vector<const toml::node*>> axis_values;
  for (std::size_t i = 0; i < axes->size(); ++i) {
    const std::string where = fmt::format("axis[{}]", i);
    const toml::table* a = axes->get(i)->as_table();
    if (!a) throw SceneError(file, where, "expected a table with key and values");
    for (auto&& [k, v] : *a)
      if (k != "key" && k != "values") throw SceneError(file, where + "." + std::string(k.str()), "unknown key");
    auto key = (*a)["key"].value<std::string>();
    const toml::array* values = (*a)["values"].as_array();
    if (!key) throw SceneError(file, where + ".key", "missing required string");
    if (!values || values->empty()) throw SceneError(file, where + ".values", "needs a non-empty array");
    SweepAxis axis{*key, {}};
    axis_values.emplace_back();
    for (auto&& v : *values) {
      axis.values.push_back(literal(v));
      axis_values.back().push_back(&v);
    }
    g.axes.push_back(std::move(axis));
  }
  std::size_t total = 1;
  for (const auto& a : g.axes) total *= a.values.size();
  if (total > 1000000) throw SceneError(file, "axis", fmt::format("{} cases is more than 1000000", total));

  const std::string base_text = read_text(g.base_scene, "base scene");
  toml::table base_table;
  try {
    base_table = toml::parse(base_text, g.base_scene.string());
  } catch (const toml::parse_error&) {
    parse_scene(base_text, g.base_scene.string());  // reports the error with its position
    throw;
  }
  for (std::size_t c = 0; c < total; ++c) {
    SweepCase sc{static_cast<int>(c), fmt::format("case_{:04d}", c), {}, {}};
    toml::table t = base_table;
    std::size_t rest = c;
    std::vector<std::size_t> pick(g.axes.size());
    for (std::size_t a = g.axes.size(); a-- > 0;) {
      pick[a] = rest % g.axes[a].values.size();
      rest /= g.axes[a].values.size();
    }
    std::optional<double> t_over_d;
    for (std::size_t a = 0; a < g.axes.size(); ++a) {
      const toml::node& v = *axis_values[a][pick[a]];
      sc.values.push_back(g.axes[a].values[pick[a]]);
      if (g.axes[a].key == "t_over_D") {
        t_over_d = v.value<double>();
        if (!t_over_d) throw SceneError(file, "t_over_D", "values must be numbers");
      } else {
        set_dotted(t, g.axes[a].key, v, file);
      }
    }
    if (t_over_d) {
      const double d = t["rings"]["outer_diameter_m"].value_or(0.0);
      set_dotted(t, "rings.wall_thickness_m", toml::value<double>(*t_over_d * d), file);
    }
    std::ostringstream text;
    text << toml::toml_formatter(t);
    sc.scene_toml = text.str();
    // Validate now: a bad combination must fail before any case runs.
    parse_scene(sc.scene_toml, fmt::format("{} ({})", file, sc.name));
    g.cases.push_back(std::move(sc));
  }
  return g;
}

SweepReport run_sweep(const SweepGrid& grid, const fs::path& out_dir, const SweepCaseRunner& runner,
                      const SweepOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  fs::create_directories(out_dir);
  SweepReport report;
  std::vector<const SweepCase*> todo;
  for (const auto& c : grid.cases) {
    if (c.index % options.ranks != options.rank) continue;
    ++report.total;
    if (fs::exists(out_dir / c.name / "summary.json")) ++report.skipped;
    else todo.push_back(&c);
  }
  const int threads = std::max(1, std::min<int>(options.threads > 0 ? options.threads
                                                                    : static_cast<int>(std::thread::hardware_concurrency()),
                                                static_cast<int>(todo.size())));
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  const bool terminal = options.progress && ::isatty(STDERR_FILENO);
  auto progress = [&] {  // called with the mutex held
    if (!options.progress) return;
    const int done = report.run + report.failed;
    const int width = 30;
    const int filled = todo.empty() ? width : static_cast<int>(width * done / static_cast<double>(todo.size()));
    const std::string line = fmt::format("sweep [{}{}] {}/{} cases run, {} skipped, {} failed",
                                         std::string(filled, '#'), std::string(width - filled, '.'),
                                         done, todo.size(), report.skipped, report.failed);
    if (terminal) fmt::print(stderr, "\r{}", line);
    else fmt::print(stderr, "{}\n", line);
  };
  {
    std::lock_guard lock(mutex);
    progress();
  }
  auto work = [&] {
    for (std::size_t i; (i = next++) < todo.size();) {
      const SweepCase& c = *todo[i];
      std::string error;
      try {
        const Scene scene = parse_scene(c.scene_toml, (out_dir / c.name / "scene.toml").string());
        ResultsDir out(out_dir / c.name);
        std::ofstream(out.file("scene.toml")) << c.scene_toml;
        runner(scene, out);
        out.commit();
        fs::remove(out_dir / (c.name + ".failed"));
      } catch (const std::exception& e) {
        error = e.what();
        std::ofstream(out_dir / (c.name + ".failed")) << error << '\n';
      }
      std::lock_guard lock(mutex);
      if (error.empty()) ++report.run;
      else {
        ++report.failed;
        report.failures.push_back(c.name + ": " + error);
      }
      progress();
    }
  };
  std::vector<std::jthread> pool;
  for (int k = 1; k < threads; ++k) pool.emplace_back(work);
  work();
  pool.clear();
  if (terminal) fmt::print(stderr, "\n");
  report.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

namespace {
void flatten(const nlohmann::json& v, const std::string& name, std::vector<std::pair<std::string, std::string>>& out) {
  if (v.is_object()) {
    for (auto it = v.begin(); it != v.end(); ++it) flatten(*it, name.empty() ? it.key() : name + "." + it.key(), out);
  } else if (v.is_array()) {
    // Per-ring arrays become name_1 … name_N; lists of records (events) stay in summary.json.
    for (const auto& e : v)
      if (e.is_structured()) return;
    for (std::size_t i = 0; i < v.size(); ++i) flatten(v[i], fmt::format("{}_{}", name, i + 1), out);
  } else if (v.is_boolean()) {
    out.emplace_back(name, v.get<bool>() ? "1" : "0");
  } else if (v.is_number_integer()) {
    out.emplace_back(name, fmt::format("{}", v.get<long long>()));
  } else if (v.is_number()) {
    out.emplace_back(name, fmt::format("{:.10g}", v.get<double>()));
  }
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}
}  // namespace

int merge_sweep(const SweepGrid& grid, const fs::path& out_dir, const fs::path& csv_file, int* missing) {
  std::vector<std::string> columns;
  std::map<std::string, std::size_t> column_index;
  std::vector<std::pair<const SweepCase*, std::map<std::string, std::string>>> rows;
  int absent = 0;
  // Staging directories of cases that finished since (a killed run's leftovers) go.
  for (const auto& e : fs::directory_iterator(out_dir)) {
    const std::string n = e.path().filename().string();
    const auto mark = n.find(".partial-");
    if (n.front() == '.' && mark != std::string::npos &&
        fs::exists(out_dir / n.substr(1, mark - 1) / "summary.json"))
      fs::remove_all(e.path());
  }
  for (const auto& c : grid.cases) {
    const fs::path summary = out_dir / c.name / "summary.json";
    if (!fs::exists(summary)) {
      ++absent;
      continue;
    }
    std::ifstream in(summary);
    const auto json = nlohmann::json::parse(in);
    std::vector<std::pair<std::string, std::string>> flat;
    flatten(json, "", flat);
    std::map<std::string, std::string> row;
    for (auto& [k, v] : flat) {
      if (!column_index.count(k)) {
        column_index[k] = columns.size();
        columns.push_back(k);
      }
      row[k] = v;
    }
    rows.emplace_back(&c, std::move(row));
  }
  std::ofstream out(csv_file);
  if (!out) throw std::runtime_error("cannot write " + csv_file.string());
  out << "case";
  for (const auto& a : grid.axes) out << ',' << csv_field(a.key);
  for (const auto& c : columns) out << ',' << csv_field(c);
  out << '\n';
  for (const auto& [c, row] : rows) {
    out << c->name;
    for (const auto& v : c->values) out << ',' << csv_field(v);
    for (const auto& col : columns) {
      auto it = row.find(col);
      out << ',' << (it == row.end() ? "" : csv_field(it->second));
    }
    out << '\n';
  }
  if (missing) *missing = absent;
  return static_cast<int>(rows.size());
}

}  // namespace ringcrush::compare
