#include "fe/fe_input.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ringcrush::fe {

void validate(const FeInput& in) {
  auto need = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("fe input: ") + what);
  };
  need(in.ring.inner_radius_m > 0 && in.ring.outer_radius_m > in.ring.inner_radius_m, "need 0 < inner radius < outer radius");
  need(in.ring.width_m > 0, "width must be positive");
  need(in.material.youngs_modulus_pa > 0, "Young's modulus must be positive");
  need(in.material.poisson_ratio > -1 && in.material.poisson_ratio < 0.5, "Poisson's ratio must lie in (-1, 0.5)");
  need(!in.material.hardening.empty(), "hardening table is empty");
  need(in.mesh.elements_around >= 2 && in.mesh.elements_around % 2 == 0, "elements_around must be even and >= 2");
  need(in.mesh.elements_through >= 1, "elements_through must be >= 1");
  need(in.mesh.grading >= 1, "grading must be >= 1");
  need(in.contact.penalty_scale > 0, "contact penalty scale must be positive");
  need(in.contact.smoothing >= 0 && in.contact.smoothing < 0.5, "contact smoothing must lie in [0, 0.5)");
  if (!(in.contact.arrival_depth > 0 && in.contact.arrival_depth <= 1))
    throw std::invalid_argument("fe input: contact arrival depth " + std::to_string(in.contact.arrival_depth) +
                                " must lie in (0, 1] (a fraction of the through-wall element depth)");
  if (!(in.contact.friction_coefficient >= 0) || !std::isfinite(in.contact.friction_coefficient))
    throw std::invalid_argument("fe input: friction coefficient " + std::to_string(in.contact.friction_coefficient) +
                                " must be finite and >= 0");
  if (!(in.contact.tangential_penalty_scale > 0) || !std::isfinite(in.contact.tangential_penalty_scale))
    throw std::invalid_argument("fe input: tangential penalty scale " +
                                std::to_string(in.contact.tangential_penalty_scale) + " must be finite and > 0");
  const auto& s = in.solver;
  need(s.crush_m > 0 && s.crush_m < 2 * in.ring.outer_radius_m, "crush must lie in (0, D)");
  need(s.min_increment > 0 && s.min_increment <= s.initial_increment && s.initial_increment <= 1,
       "increments must satisfy 0 < min <= initial <= 1");
  need(s.max_increment >= s.initial_increment && s.max_increment <= 1, "max increment must lie in [initial, 1]");
  need(s.max_iterations >= 2, "max_iterations must be >= 2");
  need(s.max_increments >= 1, "max_increments must be >= 1");
  need(s.force_tolerance_n > 0, "force tolerance must be positive");
  need(s.correction_tolerance > 0, "correction tolerance must be positive");
  need(s.frames >= 0, "frames must be >= 0");
}

}  // namespace ringcrush::fe
