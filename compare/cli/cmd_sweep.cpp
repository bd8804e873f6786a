// ringcrush sweep GRID.toml -o DIR — a parameter grid over scenes (compare/sweep.hpp): one
// case per directory, finished cases skipped on rerun, all cores, one tidy sweep.csv.
//
//   ringcrush sweep data/sweeps/thesis_velocity.toml -o results/velocity
//   mpirun -n 2 ringcrush sweep GRID -o DIR        (built with -DRINGCRUSH_WITH_MPI=ON)
//   ringcrush sweep GRID -o DIR --case $SLURM_ARRAY_TASK_ID   (one case; see README, Slurm)
//   ringcrush sweep GRID -o DIR --merge-only
//   ringcrush sweep GRID --list                 (number of cases, then each case)
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>

#include "compare/cli/commands.hpp"
#include "compare/svg_plot.hpp"
#include "compare/sweep.hpp"

#ifdef RINGCRUSH_WITH_MPI
#include <mpi.h>
#endif

namespace ringcrush::compare::cli {
namespace {

struct SweepCommand {
  std::string grid, output;
  int threads = 0;
  int only_case = -1;
  bool merge_only = false;
  bool list = false;
};

// The rank and size of this process in an MPI job (1 process without MPI). A launch by
// mpirun of a build without MPI is refused: every process would run every case.
struct Ranks {
  int rank = 0, size = 1;
#ifdef RINGCRUSH_WITH_MPI
  Ranks() {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) MPI_Init(nullptr, nullptr);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
  }
  ~Ranks() {
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (!finalised) MPI_Finalize();
  }
  void barrier() const { MPI_Barrier(MPI_COMM_WORLD); }
#else
  Ranks() {
    for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
      if (const char* v = std::getenv(var); v && std::atoi(v) > 1)
        throw std::invalid_argument(
            "launched by mpirun, but this ringcrush was built without MPI "
            "(configure with -DRINGCRUSH_WITH_MPI=ON)");
  }
  void barrier() const {}
#endif
};

void plot_first_axis(const SweepGrid& grid, const std::filesystem::path& csv, const std::filesystem::path& svg);

void run(const SweepCommand& o) {
  Ranks ranks;
  const SweepGrid grid = load_sweep_grid(o.grid);
  if (o.list) {  // "N cases", then one line per case: name and axis values
    fmt::print("{} cases\n", grid.cases.size());
    for (const auto& c : grid.cases) fmt::print("{} {}\n", c.name, fmt::join(c.values, " "));
    return;
  }
  if (o.output.empty()) throw std::invalid_argument("sweep: -o DIR is required");
  const auto& models = sweep_model_registry();
  const auto model = models.find(grid.model);
  if (model == models.end()) throw std::invalid_argument(fmt::format("sweep model \"{}\" is not available", grid.model));
  const std::filesystem::path out = o.output;
  if (!o.merge_only) {
    SweepGrid share = grid;
    if (o.only_case >= 0) {
      if (o.only_case >= static_cast<int>(grid.cases.size()))
        throw std::invalid_argument(fmt::format("--case {}: the grid has {} cases", o.only_case, grid.cases.size()));
      share.cases = {grid.cases[o.only_case]};
    }
    if (ranks.rank == 0)
      fmt::print("sweep {}: {} cases of model {} from {}; {} process(es)\n", o.grid, grid.cases.size(),
                 grid.model, grid.base_scene.string(), ranks.size);
    const SweepReport r = run_sweep(share, out, model->second,
                                    {.threads = o.threads, .rank = ranks.rank, .ranks = ranks.size,
                                     .progress = ranks.rank == 0});
    fmt::print("rank {}: {} run, {} skipped (finished before), {} failed, {:.2f} s\n", ranks.rank, r.run,
               r.skipped, r.failed, r.wall_time_s);
    for (const auto& f : r.failures) fmt::print(stderr, "  failed {}\n", f);
    ranks.barrier();
    if (o.only_case >= 0) return;  // job arrays merge once, at the end (--merge-only)
  }
  if (ranks.rank != 0) return;
  int missing = 0;
  const int merged = merge_sweep(grid, out, out / "sweep.csv", &missing);
  plot_first_axis(grid, out / "sweep.csv", out / "sweep.svg");
  fmt::print("merged {} case(s) into {}{}\n", merged, (out / "sweep.csv").string(),
             missing ? fmt::format(" ({} not finished: rerun to complete)", missing) : "");
  if (missing) throw std::runtime_error(fmt::format("{} case(s) did not finish", missing));
}

// The alternation index and ring 1's crush against the first axis, one line per value of
// the other axes, when the first axis is numeric. A `model = "compare"` sweep also plots
// where the models agree (`agree`, 1 or 0) and each model's alternation index beside the
// other's.
void plot_first_axis(const SweepGrid& grid, const std::filesystem::path& csv, const std::filesystem::path& svg) {
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  std::vector<std::string> cols;
  for (std::size_t a = 0, b; a <= header.size(); a = b + 1) {
    b = header.find(',', a);
    if (b == std::string::npos) b = header.size();
    cols.push_back(header.substr(a, b - a));
  }
  const std::size_t naxes = grid.axes.size();
  SvgPlot plot(fmt::format("Sweep over {}", grid.axes.front().key), grid.axes.front().key, "value");
  for (const char* metric : {"alternation_index", "crush_ratio_1", "agree", "agreement.alternation_index.fe",
                             "agreement.alternation_index.hinge"}) {
    const auto it = std::find(cols.begin(), cols.end(), metric);
    if (it == cols.end()) continue;
    const std::size_t mc = static_cast<std::size_t>(it - cols.begin());
    std::map<std::string, Series> groups;
    in.clear();
    in.seekg(0);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::vector<std::string> f;
      for (std::size_t a = 0, b; a <= line.size(); a = b + 1) {
        b = line.find(',', a);
        if (b == std::string::npos) b = line.size();
        f.push_back(line.substr(a, b - a));
      }
      if (f.size() <= mc || f[mc].empty()) continue;
      std::string group = metric;
      for (std::size_t k = 2; k <= naxes; ++k) group += " " + f[k];
      char* end = nullptr;
      const double x = std::strtod(f[1].c_str(), &end);
      if (end == f[1].c_str()) return;  // first axis not numeric: no plot
      auto& s = groups[group];
      s.label = group;
      s.markers = false;
      s.x.push_back(x);
      s.y.push_back(std::strtod(f[mc].c_str(), nullptr));
    }
    for (auto& [g, s] : groups) plot.add(s);
  }
  plot.write(svg);
}

void add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepCommand>();
  auto* cmd = app.add_subcommand("sweep", "Run a parameter grid of scenes (resumable; all cores; MPI optional)");
  cmd->add_option("grid", o->grid, "Grid file (TOML; see compare/sweep.hpp)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "Sweep directory (one sub-directory per case)");
  cmd->add_flag("--list", o->list, "Print the number of cases and each case's values, run nothing");
  cmd->add_option("-j,--threads", o->threads, "Cases run at once (default: all cores)")->check(CLI::Range(0, 1024));
  cmd->add_option("--case", o->only_case, "Run only case K (e.g. $SLURM_ARRAY_TASK_ID)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--merge-only", o->merge_only, "Only gather finished cases into sweep.csv");
  cmd->callback([o] { run(*o); });
}

const CommandRegistration registration{60, add_sweep_command};
}  // namespace

}  // namespace ringcrush::compare::cli
