// RunResult: what every model (fe, hinge) hands to compare/ (DESIGN.md "The contract").
// Models fill the histories and final state; compare/ computes every metric once from
// here and writes summary.json / history.csv with the stable column names of DESIGN.md.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/scene.hpp"

namespace ringcrush::compare {

struct RunEvent {
  double time_s;        // (or deflection for static runs)
  std::string kind;     // "hinge_formed", "contact_opened", "contact_closed", "ring_locked", ...
  int ring = -1;        // 0-based, −1 when not ring-specific
  std::string detail;
};

struct SolverStatistics {
  long steps = 0;
  long rejected_steps = 0;
  long newton_iterations = 0;
  double wall_time_s = 0.0;
};

struct ShapeFrame {
  double time_s = 0.0;
  std::vector<std::vector<std::array<double, 2>>> rings;  // [ring][point] full mean line, open (closed by the writer), chain frame (m)
  std::vector<std::vector<double>> plastic_rotation;      // [ring][point] rad; empty: the model has no per-point value
  std::vector<double> body_faces;                         // y of the impactor face, plates, target face (m)
};

struct RunResult {
  std::string model;           // "fe" | "hinge"
  std::string scene;           // scene name
  AnalysisType analysis = AnalysisType::Dynamic;

  // Histories, one entry per output step; the first and the last step always present.
  std::vector<double> time_s;                     // dynamic
  std::vector<double> deflection_m;               // static: driven-plate travel
  std::vector<double> force_n;                    // static: plate force (whole ring)
  std::vector<double> impactor_displacement_m;    // dynamic
  std::vector<double> impactor_velocity_m_s;      // dynamic, positive toward the chain
  std::vector<double> impactor_force_n;           // dynamic, contact force on the impactor
  std::vector<std::vector<double>> ring_crush_m;  // [ring][step], δ_i = H0 − H_i
  // Energies [step] (J): kinetic, elastic (recoverable), plastic dissipation, contact
  // (penalty energy + contact damping), numerical dissipation, external work.
  std::vector<double> kinetic_j, elastic_j, plastic_j, contact_j, numerical_j, external_work_j;
  // Explicit FE with bulk viscosity only (empty otherwise): the energy it dissipated [step].
  std::vector<double> bulk_viscous_j;

  // Final state per ring.
  std::vector<double> crush_ratio;          // c_i = δ_i / D
  std::vector<bool> wrap_around;
  std::vector<double> wrapped_angle_deg;
  std::vector<double> inverted_arc_m;
  std::vector<double> inverted_turning_deg;  // compare/measures inverted_arc: T of the lower half
  std::vector<std::string> mode;            // "flattened", "wrapped", "intact", ...
  // Final outline of each ring in the chain's frame (m): the points a model has (FE outer
  // surface nodes, polygon nodes), ordered around the ring; a half model's x ≥ 0 half only
  // (`outline_half`). Empty when the model has no shape (Levels 0, 1, shock).
  std::vector<std::vector<std::array<double, 2>>> ring_outline_m;
  bool outline_half = false;
  // Mean lines over time, for the models that have shapes (hinge Levels 2 and 3): the
  // scene's `outputs.frames` samples, first and last included, none when outputs.fields is
  // off. Written as ParaView polylines and the final-shape SVG (compare/shape_output.hpp);
  // an output, not a result: run_result_io does not store them.
  std::vector<ShapeFrame> shape_frames;

  std::vector<RunEvent> events;
  SolverStatistics statistics;
  nlohmann::json extra = nlohmann::json::object();  // model-specific summary fields
};

}  // namespace ringcrush::compare
