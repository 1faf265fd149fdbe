#include "fixed_step_integrator.hpp"

#include "stepping_integrator.hpp"

namespace contact {

namespace {

class FixedStepIntegrator final : public SteppingIntegrator {
 public:
  FixedStepIntegrator(FixedStepScheme scheme, double dt, long max_steps, OdeSystem system, double t0,
                      ConstVectorRef y0)
      : SteppingIntegrator(std::move(system), t0, y0, max_steps),
        scheme_(scheme),
        dt_(dt),
        origin_(t0),
        work_(y0.size()),
        rhs_([this](double t, ConstVectorRef y, VectorRef yd) { f(t, y, yd); }) {}

 private:
  void step(double) override {
    // The grid is origin + n dt, computed by multiplication so it does not drift.
    ++n_;
    tb_ = origin_ + static_cast<double>(n_) * dt_;
    yb_ = ya_;
    fixed_step(scheme_, rhs_, sys_.positions, ta_, tb_ - ta_, yb_, work_);
  }
  void dense(double t, VectorRef y) override {
    y = ya_;
    if (t > ta_) fixed_step(scheme_, rhs_, sys_.positions, ta_, t - ta_, y, work_);
  }
  void restarted() override {
    origin_ = ta_;
    n_ = 0;
  }

  FixedStepScheme scheme_;
  double dt_, origin_;
  long n_ = 0;
  FixedStepWork work_;
  OdeSystem::Rhs rhs_;
};

}  // namespace

std::unique_ptr<Integrator> make_fixed_step(FixedStepScheme scheme, const IntegratorOptions& o,
                                            OdeSystem system, double t0, ConstVectorRef y0) {
  return std::make_unique<FixedStepIntegrator>(scheme, o.dt, o.max_steps, std::move(system), t0, y0);
}

}  // namespace contact
