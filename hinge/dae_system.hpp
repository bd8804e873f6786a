// The interface a model offers to the implicit DAE integrator (SUNDIALS IDA):
// F(t, y, y′) = 0 with differential and algebraic components marked (THEORY §4.4).
#pragma once

#include <cstddef>
#include <vector>

namespace ringcrush::hinge {

// Where a model writes ∂F/∂y + cj ∂F/∂y′; hides whether IDA holds a dense or a band matrix.
class JacobianSink {
 public:
  virtual ~JacobianSink() = default;
  virtual void set(std::size_t row, std::size_t col, double value) = 0;
};

class DaeSystem {
 public:
  virtual ~DaeSystem() = default;

  virtual std::size_t size() const = 0;
  virtual void residual(double t, const double* y, const double* yp, double* r) = 0;

  // 1 for a differential component, 0 for an algebraic one (IDASetId). Empty: all differential.
  virtual std::vector<double> differential_mask() const { return {}; }

  // Analytic Jacobian ∂F/∂y + cj ∂F/∂y′; return false to let IDA difference quotients do it.
  virtual bool has_jacobian() const { return false; }
  virtual void jacobian(double /*t*/, double /*cj*/, const double* /*y*/, const double* /*yp*/,
                        JacobianSink& /*jac*/) {}

  // Event functions g(t, y, y′); IDA locates their sign changes (IDARootInit).
  virtual std::size_t root_count() const { return 0; }
  virtual void roots(double /*t*/, const double* /*y*/, const double* /*yp*/, double* /*g*/) {}
};

}  // namespace ringcrush::hinge
