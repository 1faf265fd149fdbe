#pragma once
// The Integrator interface for methods that only take steps (fixed-step schemes, GSL odeiv2).
// The base keeps the last step [ta, tb] and serves outputs and roots inside it from the method's
// dense evaluation: an output time inside the step is evaluated there, and a sign change of a
// root function between the current time and the step's end is narrowed to ~100 ulps of t (CVODE's
// root tolerance) on g(t, y(t)). When dense() costs a step, the root is first found on the step's
// cubic Hermite interpolant (two right-hand sides, then free) and polished on dense() from there:
// a few evaluations instead of a dozen. A root is reported at the first time where g has its new
// sign (as CVODE does), and the next advance() continues from there through the rest of the step.
#include "contact_ode/integrators/integrator.hpp"
#include "sign_change.hpp"

namespace contact {

class SteppingIntegrator : public Integrator {
 public:
  Outcome advance(double t_out) override;
  void reinit(double t, ConstVectorRef y) override;
  void set_root_directions(const std::vector<int>& directions) override { directions_ = directions; }
  double t() const override { return t_; }
  Eigen::Ref<const Vector> y() const override { return y_; }
  SolverStats stats() const override { return counts_; }

 protected:
  SteppingIntegrator(OdeSystem system, double t0, ConstVectorRef y0, long max_steps);

  // One step from (ta_, ya_) to (tb_, yb_); it may stop at t_limit but need not.
  virtual void step(double t_limit) = 0;
  // The state at t in [ta_, tb_].
  virtual void dense(double t, VectorRef y) = 0;
  // Called after a restart, to drop any history the method keeps.
  virtual void restarted() {}
  // Whether dense() is a cheap interpolant already (then roots are located on it directly).
  virtual bool dense_is_interpolant() const { return false; }
  // Whether dense() is a re-step under error control, so that it follows the flow y' = f(y) to
  // within the step's local error e: then between two of its points w apart, the cubic with slopes f
  // departs from it by about w (e/H + omega e), 1e-4 e at w = 1e-5 H even for omega H = 10. A fixed
  // step's re-step need not follow the flow (explicit Euler's is a line of slope f(ya), whatever
  // f does along it), and costs a right-hand side or none.
  virtual bool dense_follows_the_flow() const { return false; }
  // Whether one step may span more than half an oscillation of a contact (an extrapolation
  // method's can: bsimp's spanned ~1.5 of P1's, several at k = 1e8), so that a root function
  // could cross zero and back between the step's ends unseen. Such a step is retaken shorter
  // until its cubic Hermite follows its dense output (shorten_until_hermite_is_faithful), when
  // there are roots to find (without, a long accurate step is what the method is for).
  virtual bool steps_may_cross_twice() const { return false; }
  // The size below which a component counts as zero in that test (the method's absolute
  // tolerance): a ball at rest has no size of its own to be 1 % of.
  virtual double negligible_size() const { return 0.0; }
  // Told when a step was cut to length h (the next step should not propose much more).
  virtual void step_shortened(double /*h*/) {}
  // How many equal parts of a step the root functions are also looked at inside, not only at its
  // ends (1: the ends only). For a method whose dense() is cheap and exact, so that a root function
  // that grazes zero, crossing and recrossing within one step, is seen where the parts are finer.
  virtual int root_scan_parts() const { return 1; }

  // The cubic Hermite interpolant of the step from its end values and slopes (computed once).
  void hermite(double t, VectorRef y);
  // f(ta_, ya_), computed once per step: the Hermite's first slope, and the first stage of every
  // re-step from the step's start (so that a dense() by re-stepping need not evaluate it again).
  const Vector& start_slope();

  // The right-hand side, counted.
  void f(double t, ConstVectorRef y, VectorRef ydot) {
    ++counts_.rhs_evals;
    sys_.rhs(t, y, ydot);
  }

  OdeSystem sys_;
  double ta_, tb_;
  Vector ya_, yb_;
  SolverStats counts_;

 private:
  void eval_roots(double t, ConstVectorRef y, Vector& g);
  const Vector& end_slope();  // f(tb_, yb_), computed once per step
  // A root in (t_, t_hi] given the state there; fills out and moves (t_, y_) to it.
  bool locate_root(double t_hi, ConstVectorRef y_hi, Outcome& out);
  // The earliest root in (t_, t_hi] of the functions whose signs at t_ and t_hi differ (their
  // values at t_hi left in g_hi_), and the state there; +inf if none. y and g: its work space.
  double narrow_earliest_root(double t_hi, ConstVectorRef y_hi, Vector& y_root, Vector& y, Vector& g);
  // A dense() evaluation of the current step, with every root function's value there, kept so that
  // a later narrowing (another function's, or the same step's next root) starts from the tightest
  // bracket they give. Four balls ringing together cross four rate roots within one step: each was
  // narrowed over the whole step, and the three left again after each root, 10 narrowings of ~13
  // re-steps for 4 roots (98 % of RK8PD's right-hand sides on resting_cost's column at k = 1e6).
  // Now each is narrowed once (1.49e6 right-hand sides a simulated second became 3.8e5; 1.2e5 with
  // the bracket's cubic finishing, dense_follows_the_flow).
  struct Trial {
    double t;
    Vector y, g;
  };
  void keep_trial(double t, ConstVectorRef y, ConstVectorRef g);
  struct KnownBracket {
    SignChange b;
    const Vector* y_hi;  // the kept trial's state at b.hi; null: b.hi is the narrowing's t_hi
    const Vector* y_lo;  // the kept trial's state at b.lo; null: b.lo is t_
  };
  // Root function k's first sign change in (t_, t_hi] as far as the kept trials tell.
  KnownBracket known_bracket(Eigen::Index k, double t_hi) const;
  // Whether a sign change of root function i in direction dir (+1 rising, -1 falling, 0 none)
  // counts, given the directions asked for.
  bool allowed(std::size_t i, int dir) const;
  // Moves (t_hi, y_hi) back to the first inner point of root_scan_parts() where a root function
  // has changed sign since t_, if any.
  void scan_for_crossing(double& t_hi, Vector& y_hi);
  // step() from (ta_, ya_), then the checks every step gets: slopes dropped, a finite state.
  void take_step(double t_limit);
  void shorten_until_hermite_is_faithful();

  double t_;
  Vector y_, g_, g_hi_, f_a_, f_b_;
  Vector y_scan_, g_scan_;     // the root scan's and the narrowing's work space
  std::vector<Trial> trials_;  // the current step's kept trials: the first trial_count_ (storage reused)
  std::size_t trial_count_ = 0;
  bool have_start_slope_ = false, have_end_slope_ = false;
  std::vector<int> directions_;
  long max_steps_;
};

}  // namespace contact
