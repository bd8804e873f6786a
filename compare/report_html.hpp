// report.html of `ringcrush compare` (issue 8 item 2): one self-contained page a person opens
// in a browser — the verdicts with their thresholds, the per-ring table, and inline SVG
// charts (crush per ring FE vs hinge, impactor velocity and force, energies, final ring
// shapes). No scripts, no external files.
#pragma once

#include <string>

#include "compare/agreement.hpp"
#include "compare/run_result.hpp"
#include "compare/scene.hpp"

namespace ringcrush::compare {

struct ReportInput {
  const Scene* scene = nullptr;
  const RunResult* fe = nullptr;
  const RunResult* hinge = nullptr;
  const Agreement* agreement = nullptr;
  AgreementThresholds thresholds;
  double fe_wall_time_s = 0, hinge_wall_time_s = 0;
  bool fe_from_cache = false;
  std::string code_version;
};

std::string render_report_html(const ReportInput& in);

}  // namespace ringcrush::compare
