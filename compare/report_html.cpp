#include "compare/report_html.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "compare/measures.hpp"
#include "compare/svg_charts.hpp"
#include "compare/svg_plot.hpp"

namespace ringcrush::compare {
namespace {

std::vector<double> milliseconds(const std::vector<double>& t) {
  std::vector<double> ms;
  for (double v : t) ms.push_back(1e3 * v);
  return ms;
}

std::string joints_name(JointType j) {
  switch (j) {
    case JointType::Welded: return "welded";
    case JointType::Free: return "free";
    case JointType::Plates: return "plates";
  }
  return "?";
}

std::string history_chart(const std::string& title, const std::string& y_label, const RunResult& fe,
                          const RunResult& hinge, const std::vector<double> RunResult::*member) {
  SvgPlot p(title, "time (ms)", y_label);
  if (!(fe.*member).empty()) p.add({"FE", milliseconds(fe.time_s), fe.*member});
  if (!(hinge.*member).empty()) p.add({"hinge", milliseconds(hinge.time_s), hinge.*member, true});
  return p.render();
}

}  // namespace

std::string render_report_html(const ReportInput& in) {
  if (!in.scene || !in.fe || !in.hinge || !in.agreement) throw std::invalid_argument("report: missing input");
  const Scene& s = *in.scene;
  const RunResult& fe = *in.fe;
  const RunResult& hinge = *in.hinge;
  const Agreement& a = *in.agreement;

  std::string h;
  h += "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n";
  h += fmt::format("<title>ringcrush compare — {}</title>\n", xml_escape(s.name));
  h += "<style>body{font-family:sans-serif;max-width:1000px;margin:2em auto;color:#222}"
       "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:4px 8px;text-align:right}"
       "th{background:#f4f4f4}td.l,th.l{text-align:left}.pass{color:#17752b;font-weight:bold}"
       ".fail{color:#b3141b;font-weight:bold}figure{margin:1em 0}</style></head><body>\n";
  h += fmt::format("<h1>FE against hinge model: {}</h1>\n<p>{}</p>\n", xml_escape(s.name), xml_escape(s.title));
  h += fmt::format(
      "<p>{} rings, D = {:.1f} mm, t = {:.2f} mm, L = {:.1f} mm, joints {}; impactor {:.3f} kg at {:.1f} m/s; far end "
      "{}.</p>\n",
      s.rings.count, 1e3 * s.rings.outer_diameter_m, 1e3 * s.rings.wall_thickness_m, 1e3 * s.rings.width_m,
      joints_name(s.joints.type), s.impactor ? s.impactor->mass_kg : 0.0, s.impactor ? s.impactor->velocity_m_s : 0.0,
      s.far_end == FarEnd::Fixed ? "fixed target" : "free");
  h += fmt::format("<p>Run time: FE {:.3g} s{}, hinge (level {}) {:.3g} s. Code {}.</p>\n", in.fe_wall_time_s,
                   in.fe_from_cache ? " (served from the result cache; original run time)" : "", xml_escape(s.hinge.level),
                   in.hinge_wall_time_s, xml_escape(in.code_version));
  h += fmt::format("<h2>Verdict: <span class=\"{}\">{}</span></h2>\n", a.agree ? "pass" : "fail",
                   a.agree ? "the models agree" : "the models disagree");
  h += "<table><tr><th class=\"l\">check</th><th>value</th><th>threshold</th><th>result</th><th class=\"l\">detail</th></tr>\n";
  for (const auto& v : a.verdicts)
    h += fmt::format("<tr><td class=\"l\">{}</td><td>{:.3g}</td><td>{:.3g}</td><td class=\"{}\">{}</td><td "
                     "class=\"l\">{}</td></tr>\n",
                     xml_escape(v.description), v.value, v.threshold, v.pass ? "pass" : "fail", v.pass ? "pass" : "FAIL",
                     xml_escape(v.detail));
  h += "</table>\n";
  h += "<h2>Per ring</h2>\n<table><tr><th>ring</th><th>FE crush ratio</th><th>hinge crush ratio</th>"
       "<th>difference</th><th>FE wrap</th><th>hinge wrap</th><th class=\"l\">FE mode</th><th class=\"l\">hinge "
       "mode</th></tr>\n";
  for (const auto& r : a.rings)
    h += fmt::format("<tr><td>{}</td><td>{:.3f}</td><td>{:.3f}</td><td>{:+.3f}</td><td>{}</td><td>{}</td><td "
                     "class=\"l\">{}</td><td class=\"l\">{}</td></tr>\n",
                     r.ring, r.fe_crush_ratio, r.hinge_crush_ratio, r.difference, r.fe_wrap ? "yes" : "no",
                     r.hinge_wrap ? "yes" : "no", xml_escape(r.fe_mode), xml_escape(r.hinge_mode));
  h += "</table>\n";
  h += fmt::format("<p>Alternation index: FE {:.2f}, hinge {:.2f} (a chain alternates above {:.2f}). Arrest time: FE "
                   "{}, hinge {}.</p>\n",
                   a.fe_alternation_index, a.hinge_alternation_index, alternation_threshold,
                   a.fe_arrest_time_s >= 0 ? fmt::format("{:.2f} ms", 1e3 * a.fe_arrest_time_s) : "not reached",
                   a.hinge_arrest_time_s >= 0 ? fmt::format("{:.2f} ms", 1e3 * a.hinge_arrest_time_s) : "not reached");

  std::vector<std::string> categories;
  std::vector<double> cf, ch;
  for (const auto& r : a.rings) {
    categories.push_back(fmt::format("ring {}", r.ring));
    cf.push_back(r.fe_crush_ratio);
    ch.push_back(r.hinge_crush_ratio);
  }
  h += "<h2>Charts</h2>\n<figure>" +
       render_bar_chart("Final crush ratio per ring", "crush ratio δ/D", categories, {{"FE", cf}, {"hinge", ch}}) +
       "</figure>\n";
  h += "<figure>" + history_chart("Impactor velocity", "velocity (m/s)", fe, hinge, &RunResult::impactor_velocity_m_s) +
       "</figure>\n";
  h += "<figure>" + history_chart("Impactor force", "force (N)", fe, hinge, &RunResult::impactor_force_n) +
       "</figure>\n";
  {
    SvgPlot p("Energies", "time (ms)", "energy (J)");
    const auto mf = milliseconds(fe.time_s), mh = milliseconds(hinge.time_s);
    if (!fe.kinetic_j.empty()) p.add({"FE kinetic", mf, fe.kinetic_j});
    if (!fe.plastic_j.empty()) p.add({"FE plastic", mf, fe.plastic_j});
    if (!hinge.kinetic_j.empty()) p.add({"hinge kinetic", mh, hinge.kinetic_j, true});
    if (!hinge.plastic_j.empty()) p.add({"hinge plastic", mh, hinge.plastic_j, true});
    h += "<figure>" + p.render() + "</figure>\n";
  }
  std::vector<OutlineSet> sets;
  if (!fe.ring_outline_m.empty()) sets.push_back({"FE (outer surface)", fe.ring_outline_m, fe.outline_half, false});
  if (!hinge.ring_outline_m.empty())
    sets.push_back({"hinge (polygon nodes)", hinge.ring_outline_m, hinge.outline_half, true});
  if (!sets.empty())
    h += "<figure>" + render_outlines("Ring shapes at the end", sets) + "</figure>\n";
  else
    h += "<p>Neither model reported ring shapes (hinge levels 0, 1 and shock have none).</p>\n";
  h += "<p>Machine-readable: summary.json (\"agreement\"), fe/ and hinge/ results directories.</p>\n";
  h += "</body></html>\n";
  return h;
}

}  // namespace ringcrush::compare
