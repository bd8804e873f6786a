#include "compare/through_wall_section.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <mutex>
#include <set>

#include "compare/fe_integration.hpp"
#include "fe/element/through_wall_plastic_moment.hpp"

namespace ringcrush::compare {
namespace {

const char* rule_key(Integration i) {
  switch (i) {
    case Integration::Full: return "full";
    case Integration::Reduced: return "reduced";
    case Integration::Selective: return "selective";
  }
  return "?";
}

std::string points_across(const Scene& s) {
  const int points = fe::gauss_points_through(fe_integration(s.fe.integration));
  return s.fe.elements_through == 1
             ? fmt::format("{} Gauss points across one element", points)
             : fmt::format("{} Gauss points across each of {} elements", points, s.fe.elements_through);
}

}  // namespace

double fe_plastic_moment_factor(const Scene& s) {
  return fe::through_wall_plastic_moment(s.fe.elements_through, fe_integration(s.fe.integration));
}

std::string through_wall_section_line(const Scene& s) {
  return fmt::format("through-wall section: plastic moment {:.3f} M0 ({})", fe_plastic_moment_factor(s),
                     points_across(s));
}

std::optional<std::string> through_wall_warning(const Scene& s) {
  const double f = fe_plastic_moment_factor(s);
  if (s.rings.count < 2 || std::abs(f - 1) <= through_wall_warning_tolerance) return std::nullopt;
  const std::string mesh =
      s.fe.elements_through == 1
          ? std::string("one CPS8 through the wall (fe.elements_through = 1: the thesis's mesh, which "
                        "thesis_dynamic.toml and thesis_static.toml keep to reproduce the thesis)")
          : fmt::format("{} CPS8 through the wall (fe.elements_through = {})", s.fe.elements_through,
                        s.fe.elements_through);
  return fmt::format(
      "warning: {}: {}, integration \"{}\": the FE section's fully plastic moment is {:.3f} M0 ({}), so its "
      "rings are {} in bending than the hinge model's and yield across the wall at once; FE against the hinge "
      "model then compares the mesh (README \"FE against the hinge model\"). fe.elements_through = 2 carries M0.",
      s.source.empty() ? s.name : s.source.string(), mesh, rule_key(s.fe.integration), f, points_across(s),
      f > 1 ? "stronger" : "weaker");
}

void warn_through_wall_once(const Scene& s) {
  static std::mutex mutex;
  static std::set<std::string> warned;
  const auto w = through_wall_warning(s);
  if (!w) return;
  std::lock_guard lock(mutex);
  if (!warned.insert(s.source.empty() ? s.name : s.source.string()).second) return;
  std::fprintf(stderr, "%s\n", w->c_str());
}

}  // namespace ringcrush::compare
