#pragma once
// A linear contact (stiffness k [N/m], damping c [N s/m], effective mass m [kg]) expressed in the
// conventions of popular engines, and back. Each pair round-trips (test_engine_conventions).
//
// ODE / Bullet, at step h [s] (ODE manual, "Soft constraint and constraint force mixing": a
// spring-damper is simulated exactly by ERP = h k / (h k + c), CFM = 1 / (h k + c); Bullet uses
// ODE's definitions):
//   erp = h k / (h k + c),  cfm = 1 / (h k + c)   <=>  k = erp / (h cfm),  c = (1 - erp) / cfm.
// MuJoCo solref (MuJoCo documentation, "Solver parameters": reference acceleration
// a_ref = -b v - k r with, for solref = (timeconst, dampratio), b = 2 / (dmax timeconst) and
// k = d(r) / (dmax^2 timeconst^2 dampratio^2); for solref = (-stiffness, -damping), b = damping / dmax
// and k = stiffness d(r) / dmax^2). Taken here with impedance d = dmax = 1 (solimp width 0), so
// the reference is the mass-normalised spring: k/m and c/m:
//   timeconst = 2 m / c,  dampratio = c / (2 sqrt(k m))  (= the damping ratio zeta);
//   stiffness = k / m,    damping = c / m.
// Box2D (v3, b2MakeSoft in solver.h: soft contact given as hertz and damping ratio, with
// omega = 2 pi hertz):
//   hertz = sqrt(k/m) / (2 pi),  damping_ratio = c / (2 sqrt(k m)).
// Drake (MultibodyPlant::set_penetration_allowance and EstimatePointContactParameters: a body
// of mass m resting under gravity g penetrates delta_a, so k = m g / delta_a; Drake then sets its
// Hunt–Crossley dissipation to d = 1 / (omega delta_a), omega = sqrt(k/m)):
//   penetration_allowance = m g / k.

namespace contact {

// The damping ratio zeta = c / (2 sqrt(k m)), formed without k m (which underflows for a light
// body on a soft spring).
double damping_ratio(double k, double c, double m);

struct OdeErpCfm {
  double erp;  // error reduction parameter, in (0, 1]
  double cfm;  // constraint force mixing [m / (N s)]
};
OdeErpCfm to_ode(double k, double c, double h);
void from_ode(const OdeErpCfm& p, double h, double& k, double& c);

struct MujocoSolref {
  double timeconst;  // [s]; infinite for c = 0
  double dampratio;
};
MujocoSolref to_mujoco(double k, double c, double m);
void from_mujoco(const MujocoSolref& p, double m, double& k, double& c);

struct MujocoDirect {
  double stiffness;  // k / m [1/s^2]  (given to MuJoCo as solref[0] = -stiffness)
  double damping;    // c / m [1/s]    (solref[1] = -damping)
};
MujocoDirect to_mujoco_direct(double k, double c, double m);
void from_mujoco_direct(const MujocoDirect& p, double m, double& k, double& c);

struct Box2dSoft {
  double hertz;  // contact frequency [Hz]
  double damping_ratio;
};
Box2dSoft to_box2d(double k, double c, double m);
void from_box2d(const Box2dSoft& p, double m, double& k, double& c);

struct DrakeContact {
  double penetration_allowance;  // [m]
  double dissipation;            // Drake's Hunt–Crossley d [s/m] that the allowance implies
};
DrakeContact to_drake(double k, double m, double g);
double drake_stiffness(double penetration_allowance, double m, double g);

}  // namespace contact
