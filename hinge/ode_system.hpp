// The interface a model offers to explicit integrators (Boost.Odeint): y′ = f(t, y).
#pragma once

#include <cstddef>

namespace ringcrush::hinge {

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual std::size_t size() const = 0;
  virtual void rhs(double t, const double* y, double* dydt) = 0;
};

}  // namespace ringcrush::hinge
