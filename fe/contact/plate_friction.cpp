#include "fe/contact/plate_friction.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace ringcrush::fe {

PlateFriction plate_friction(double x, double fn, double dfn_dy, double kt, double mu, double anchor_n) {
  if (!(mu >= 0) || !std::isfinite(mu))
    throw std::invalid_argument(fmt::format("plate friction: friction coefficient {} must be finite and >= 0", mu));
  if (!(kt > 0) || !std::isfinite(kt))
    throw std::invalid_argument(fmt::format("plate friction: tangential penalty {} must be finite and > 0", kt));
  if (!std::isfinite(x) || !std::isfinite(fn) || !std::isfinite(dfn_dy) || !std::isfinite(anchor_n))
    throw std::invalid_argument("plate friction: non-finite position, normal force or anchor");
  PlateFriction out;
  const double trial = -kt * (x - anchor_n);
  const double limit = mu * std::max(fn, 0.0);
  if (std::abs(trial) <= limit) {
    out.traction = trial;
    out.anchor = anchor_n;
    out.dr_dx = kt;
  } else {
    // Return to the slip surface: the direction of the trial force is kept (radial return
    // in one dimension), its size becomes μ f_n.
    const double s = trial > 0 ? 1.0 : -1.0;
    out.slipping = true;
    out.traction = s * limit;
    out.anchor = x + out.traction / kt;
    out.dr_dy = fn > 0 ? -mu * s * dfn_dy : 0.0;
    out.dissipation = limit * std::abs(out.anchor - anchor_n);
  }
  const double e = x - out.anchor;
  out.stored_energy = 0.5 * kt * e * e;
  return out;
}

}  // namespace ringcrush::fe
