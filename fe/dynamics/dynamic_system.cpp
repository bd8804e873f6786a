#include "fe/dynamics/dynamic_system.hpp"

#include "fe/dynamics/explicit_step_end.hpp"

namespace ringcrush::fe {

// The unfused reference: the whole force first, then the step's end over the dofs in order.
void DynamicSystem::evaluate_explicit(const Eigen::VectorXd& u, SystemEvaluation& out, ExplicitStepEnd& end) {
  evaluate(u, false, out);
  end.range(0, out.force.size(), out.force.data(),
            out.viscous_force.size() == out.force.size() ? out.viscous_force.data() : nullptr);
}

}  // namespace ringcrush::fe
