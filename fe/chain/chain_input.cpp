#include "fe/chain/chain_input.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace ringcrush::fe {

void validate(const ChainInput& in) {
  auto need = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("chain input: " + what);
  };
  need(in.rings >= 1, fmt::format("rings must be >= 1 (got {})", in.rings));
  need(in.step_bound_margin >= 1 && in.step_bound_margin <= 2,
       fmt::format("step_bound_margin must lie in [1, 2] (got {})", in.step_bound_margin));
  validate(in.mass_scaling);
  need(in.contact_penalty_step_fraction == 0 ||
           (in.contact_penalty_step_fraction > 0 && in.contact_penalty_step_fraction <= 0.5),
       fmt::format("contact_penalty_step_fraction must be 0 (off) or lie in (0, 0.5] (got {})",
                   in.contact_penalty_step_fraction));
  need(in.threads >= 0 && in.threads <= 2, fmt::format("threads must be 0 (automatic), 1 or 2 (got {})", in.threads));
  // Ring, material, mesh and contact: the same rules as the single-ring model.
  FeInput single;
  single.ring = in.ring;
  single.material = in.material;
  single.mesh = in.mesh;
  single.integration = in.integration;
  single.contact = in.contact;
  single.solver.crush_m = in.ring.outer_radius_m;  // the static solver is not used here
  validate(single);
  need(std::isfinite(in.density_kg_m3) && in.density_kg_m3 > 0,
       fmt::format("density must be positive (got {} kg/m3)", in.density_kg_m3));
  need(std::isfinite(in.impactor_mass_kg) && in.impactor_mass_kg > 0,
       fmt::format("impactor mass must be positive (got {} kg)", in.impactor_mass_kg));
  need(std::isfinite(in.impactor_velocity_m_s) && in.impactor_velocity_m_s >= 0,
       fmt::format("impactor velocity (toward the chain) must be >= 0 (got {} m/s)", in.impactor_velocity_m_s));
  need(std::isfinite(in.bulk_viscosity) && in.bulk_viscosity >= 0 && in.bulk_viscosity < 1,
       fmt::format("bulk viscosity b1 must be in [0, 1) (got {})", in.bulk_viscosity));
  const double d = 2 * in.ring.outer_radius_m;
  // Tolerance for "equal" lengths: scene values are given to a few digits (50.8 mm = 2 in).
  const double tol = 1e-6 * d;
  need(std::isfinite(in.pitch_m) && in.pitch_m > 0, fmt::format("pitch must be positive (got {} m)", in.pitch_m));
  switch (in.joints) {
    case JointKind::Welded:
      // The tie joins ring i's bottom outer node and ring i+1's top outer node (the thesis's
      // *MPC 501–1597, ...), which coincide only when the rings touch.
      need(std::abs(in.pitch_m - d) <= tol,
           fmt::format("welded joints need pitch = 2 x outer radius = {} m (got {} m)", d, in.pitch_m));
      break;
    case JointKind::Free:
      need(in.pitch_m >= d - tol,
           fmt::format("free joints need pitch >= 2 x outer radius = {} m, rings may not overlap (got {} m)", d,
                       in.pitch_m));
      break;
    case JointKind::Plates:
      need(std::isfinite(in.plate_thickness_m) && in.plate_thickness_m > 0,
           fmt::format("plates joints need a positive plate thickness (got {} m)", in.plate_thickness_m));
      need(std::isfinite(in.plate_mass_kg) && in.plate_mass_kg > 0,
           fmt::format("plates joints need a positive plate mass (got {} kg)", in.plate_mass_kg));
      need(std::abs(in.pitch_m - d - in.plate_thickness_m) <= tol,
           fmt::format("plates joints need pitch = 2 x outer radius + plate thickness = {} m (got {} m)",
                       d + in.plate_thickness_m, in.pitch_m));
      break;
  }
}

}  // namespace ringcrush::fe
