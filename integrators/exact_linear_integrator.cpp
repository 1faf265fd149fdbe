#include "exact_linear_integrator.hpp"

#include "dense_limit.hpp"
#include "stepping_integrator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace contact {

namespace {

using Index = Eigen::Index;
constexpr int kMaxTerms = 60;   // Taylor terms of one step; h rho <= 1 needs about 20
constexpr int kRateTerms = 24;  // powers of A whose growth estimates rho
constexpr Index kMaxQuadratureStates = 64;
constexpr std::size_t kKeptSegments = 4;  // a ball's flight and contact; a short chain's few modes
constexpr double kEps = std::numeric_limits<double>::epsilon();

// The largest magnitude of a vector expression, without a temporary.
template <typename V>
double max_abs(const V& v) {
  return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff();
}

// Eigen's indexed view (v(p) with a std::vector p) copies its index vector, a heap allocation, each
// time it is formed: at every step and root check, malloc and free were 28 % of a P1 solve, so the
// per-step code gathers, scatters and measures the entries p by hand.
void gather(const Vector& from, const std::vector<Index>& at, Vector& to) {
  to.resize(static_cast<Index>(at.size()));
  for (std::size_t i = 0; i < at.size(); ++i) to[static_cast<Index>(i)] = from[at[i]];
}

double max_abs_at(const Vector& v, const std::vector<Index>& at) {
  double largest = 0;
  for (const Index i : at) largest = std::max(largest, std::abs(v[i]));
  return largest;
}

// |value - predicted| within `rel` of the size of the terms that formed them.
bool agrees(double value, double predicted, double size, double rel) {
  return std::abs(value - predicted) <= rel * size + 1e-300;
}

// The right-hand side between two restarts, y_p' = f0_p + A (y_p - y0_p) for the affine entries p
// and y_q' = f0_q + g_q . u + u' H_q u (u = y_p - y0_p) for each quadrature q.
struct Segment {
  Matrix A;
  Vector y0, f0;
  Matrix G;               // the quadratures' gradients at y0, a row each
  std::vector<Matrix> H;  // and their Hessians / 2
  double rho = 0;         // A's spectral radius: the segment's fastest frequency
};

class ExactLinearIntegrator final : public SteppingIntegrator {
 public:
  ExactLinearIntegrator(const IntegratorOptions& o, OdeSystem system, double t0, ConstVectorRef y0)
      : SteppingIntegrator(std::move(system), t0, y0, o.max_steps), max_step_(o.max_step), atol_(o.atol) {
    const Index n = y0.size();
    const bool marked = sys_.quadratures.size() == n;
    for (Index i = 0; i < n; ++i) (marked && sys_.quadratures[i] ? q_ : p_).push_back(i);
    // Each restart holds dense n x n matrices: the Jacobian, a probe's Jacobian and the kept
    // segments' A (their quadratures' Hessians are small: m <= kMaxQuadratureStates). Nothing
    // counted them: a 4e5-ball chain asked for 5 TB at its first step and ended in std::bad_alloc,
    // and a few thousand balls would be granted by overcommit.
    refuse_dense_beyond_limit(static_cast<double>(n), 2 + static_cast<int>(kKeptSegments),
                              "use an adaptive integrator (cvode-bdf), whose band, klu or gmres linear "
                              "solver scales with n");
  }

  void reinit(double t, ConstVectorRef y) override {
    SteppingIntegrator::reinit(t, y);
    seg_ = nullptr;  // a restart: the right-hand side may have changed (a switch)
  }

  SolverStats stats() const override {
    SolverStats s = SteppingIntegrator::stats();
    s.jac_evals = jac_evals_;
    return s;
  }

 private:
  [[noreturn]] void refuse(const std::string& why) const {
    throw SolverFailure(Status::SolverError, ta_, "exact-linear: " + why);
  }

  Vector rhs_at(double t, const Vector& y) {
    Vector out(y.size());
    f(t, y, out);
    return out;
  }

  Matrix affine_block(double t, const Vector& y) {
    sys_.jacobian(t, y, J_);
    ++jac_evals_;
    Jd_ = J_;
    if (!q_.empty() && !Jd_(p_, q_).isZero(0))
      refuse("a quadrature entry (the energy ledger) feeds the other entries' derivatives");
    return Jd_(p_, p_);
  }

  // The first entry of f (at y, given there) that segment s does not predict, or -1: a
  // quadrature's index is reported as is. A test of structure, not of accuracy: rounding moves f
  // by ~1e-15 of the terms that form it, another mode or a nonlinear law by a share of order one,
  // so 1e-9 (1e-8 for the quadratic forms, formed by polarisation) tells them apart with margin.
  Index mismatch(const Segment& s, const Vector& y, const Vector& fy) {
    const Index m = static_cast<Index>(p_.size());
    offset_from(s, y);
    w_.resize(m);  // |u| + |y0|: the size of the state the terms are formed from
    for (Index i = 0; i < m; ++i) w_[i] = std::abs(u_[i]) + std::abs(s.y0[p_[i]]);
    tmp_.noalias() = s.A * u_;
    for (Index i = 0; i < m; ++i) {
      const double size = std::abs(s.f0[p_[i]]) + s.A.row(i).cwiseAbs().dot(w_);
      if (!agrees(fy[p_[i]], s.f0[p_[i]] + tmp_[i], size, 1e-9)) return p_[i];
    }
    for (std::size_t r = 0; r < q_.size(); ++r) {
      const auto row = static_cast<Index>(r);
      const Matrix& H = s.H[r];
      hu_.noalias() = H * u_;
      double quadratic_size = 0;  // |u|' |H| |u|
      for (Index l = 0; l < m; ++l) {
        double column = 0;
        for (Index k = 0; k < m; ++k) column += std::abs(H(k, l)) * std::abs(u_[k]);
        quadratic_size += column * std::abs(u_[l]);
      }
      const double predicted = s.f0[q_[r]] + s.G.row(row).dot(u_) + u_.dot(hu_);
      const double size = std::abs(s.f0[q_[r]]) + s.G.row(row).cwiseAbs().dot(u_.cwiseAbs()) + quadratic_size;
      if (!agrees(fy[q_[r]], predicted, size, 1e-8)) return q_[r];
    }
    return -1;
  }

  // u_ = y_p - y0_p: the affine entries' offset from the segment's start.
  void offset_from(const Segment& s, const Vector& y) {
    u_.resize(static_cast<Index>(p_.size()));
    for (Index i = 0; i < u_.size(); ++i) u_[i] = y[p_[i]] - s.y0[p_[i]];
  }

  // The segment that starts at (ta_, ya_): one kept from an earlier restart if it has the same A
  // and predicts f here (the flight and the contact of a bouncing ball recur), else a new one.
  void enter_segment() {
    if (!sys_.jacobian) refuse("needs the system's Jacobian (the A of y' = A y + b)");
    Matrix A = affine_block(ta_, ya_);
    const Vector f0 = rhs_at(ta_, ya_);
    for (Segment& s : kept_)
      if (s.A == A && mismatch(s, ya_, f0) < 0) {
        seg_ = &s;
        return;
      }
    if (kept_.size() == kKeptSegments) kept_.erase(kept_.begin());
    kept_.push_back(new_segment(std::move(A), f0));
    seg_ = &kept_.back();
  }

  // A new segment, checked on one probe off the state and later in time: the same Jacobian, and f
  // moved by A d exactly, or the system is not affine (or not autonomous) and is refused.
  Segment new_segment(Matrix A, const Vector& f0) {
    const Index n = ya_.size(), m = static_cast<Index>(p_.size());
    Segment s{.A = std::move(A), .y0 = ya_, .f0 = f0};
    Vector d = Vector::Zero(n);
    for (Index k = 0; k < m; ++k)
      d[p_[k]] = (k % 2 == 0 ? 1e-3 : -7e-4) * std::max(1.0, std::abs(ya_[p_[k]]));
    const double t_probe = ta_ + 1e-3 * std::max(1.0, std::abs(ta_));
    const Vector y_probe = ya_ + d;
    const Matrix moved = affine_block(t_probe, y_probe);
    // An affine system's analytic Jacobian is the same matrix wherever it is formed (1e-12 of the
    // row's largest entry allows for rounding in its assembly).
    for (Index i = 0; i < m; ++i) {
      const double row = s.A.row(i).cwiseAbs().maxCoeff();
      for (Index j = 0; j < m; ++j)
        if (!agrees(moved(i, j), s.A(i, j), row, 1e-12))
          refuse(
              fmt::format("the right-hand side is not affine in the state (its Jacobian's entry ({}, {}) "
                          "moved from {:.6g} to {:.6g} on a probe; a nonlinear contact law?): use an "
                          "adaptive integrator",
                          p_[i], p_[j], s.A(i, j), moved(i, j)));
    }
    const Vector f_probe = rhs_at(t_probe, y_probe);
    const Vector Ad = s.A * d(p_);
    for (Index i = 0; i < m; ++i) {
      const double size = std::abs(f0[p_[i]]) + (s.A.row(i).cwiseAbs() * y_probe(p_).cwiseAbs()).value();
      if (!agrees(f_probe[p_[i]], f0[p_[i]] + Ad[i], size, 1e-9))
        refuse(
            fmt::format("the right-hand side of entry {} is not A y + b with A its Jacobian, or depends on "
                        "time ({:.9g} against {:.9g} on a probe)",
                        p_[i], f_probe[p_[i]], f0[p_[i]] + Ad[i]));
    }
    quadratic_forms(s);
    const Index q = mismatch(s, y_probe, f_probe);
    if (q >= 0)
      refuse(
          fmt::format("quadrature entry {} (the energy ledger) is not a quadratic form of the others "
                      "(checked on a probe)",
                      q));
    s.rho = spectral_radius(s.A);
    return s;
  }

  // Each quadrature's gradient and Hessian by polarisation on probes (exact for a quadratic): m (m
  // + 3) / 2 right-hand sides. A probe is at least the entry's own size: unit probes on a state far
  // larger than 1 took the Hessian from differences of nearly equal ledger rates, off by their
  // rounding (a drop sped up 1e4 times, its speeds 4e4 m/s, was refused as not quadratic); a probe
  // larger than the state costs nothing on an exact quadratic.
  void quadratic_forms(Segment& s) {
    const Index m = static_cast<Index>(p_.size()), r = static_cast<Index>(q_.size());
    if (r > 0 && m > kMaxQuadratureStates)  // (before the Hessians' m x m storage is allocated)
      refuse(
          fmt::format("forms its quadratures (the energy ledger) from m (m + 3) / 2 right-hand sides at "
                      "every restart; m = {} entries is beyond its {}: use an adaptive integrator",
                      m, kMaxQuadratureStates));
    s.G = Matrix::Zero(r, m);
    s.H.assign(q_.size(), Matrix::Zero(m, m));
    if (q_.empty()) return;
    const Vector c = s.f0(q_);
    Vector probe(m);
    for (Index k = 0; k < m; ++k) probe[k] = std::max(1.0, std::abs(ya_[p_[k]]));
    auto at = [&](Index k, double dk, Index l, double dl) -> Vector {
      Vector y = ya_;
      y[p_[k]] += dk;
      if (l >= 0) y[p_[l]] += dl;
      return rhs_at(ta_, y)(q_);
    };
    for (Index k = 0; k < m; ++k) {
      const double h = probe[k];
      const Vector plus = at(k, h, -1, 0), minus = at(k, -h, -1, 0);
      s.G.col(k) = 0.5 * (plus - minus) / h;
      for (Index i = 0; i < r; ++i)
        s.H[static_cast<std::size_t>(i)](k, k) = 0.5 * (plus[i] + minus[i] - 2 * c[i]) / (h * h);
    }
    for (Index k = 0; k < m; ++k)
      for (Index l = k + 1; l < m; ++l) {
        const double hk = probe[k], hl = probe[l];
        const Vector both = at(k, hk, l, hl);
        for (Index i = 0; i < r; ++i) {
          Matrix& H = s.H[static_cast<std::size_t>(i)];
          H(k, l) = H(l, k) =
              0.5 *
              (both[i] - c[i] - s.G(i, k) * hk - s.G(i, l) * hl - H(k, k) * hk * hk - H(l, l) * hl * hl) /
              (hk * hl);
        }
      }
  }

  // The growth rate of ||A^j u|| for a generic u: A's spectral radius, 0 for a nilpotent A (a free
  // flight), whose series ends. Normalised at each power, so a stiff A does not overflow. u must
  // have a share of every mode: a uniform one is a rigid translation, which no spring between
  // bodies stretches (a falling column's A took it to zero in two powers, and its steps spanned
  // its contacts' oscillations), so its entries are spread by a fixed sequence. A zero growth is
  // taken only if A's own powers vanish; else the bound ||A|| stands in (short steps, never long).
  static double spectral_radius(const Matrix& A) {
    Vector u(A.rows());
    for (Index i = 0; i < u.size(); ++i) u[i] = 1.0 + 0.5 * std::sin(1.7 * static_cast<double>(i) + 0.3);
    double log_growth = 0;
    for (int j = 0; j < kRateTerms; ++j) {
      u = A * u;
      const double size = max_abs(u);
      if (!(size > 0)) return nilpotent(A) ? 0.0 : A.cwiseAbs().rowwise().sum().maxCoeff();
      log_growth += std::log(size);
      u /= size;
    }
    return std::exp(log_growth / kRateTerms);
  }

  static bool nilpotent(const Matrix& A) {
    Matrix power = A;
    for (Index j = 0; j < A.rows(); ++j) {
      if (power.isZero(0)) return true;
      power = A * power;
    }
    return power.isZero(0);
  }

  void step(double t_limit) override {
    if (!seg_) enter_segment();
    // (Not start_slope(): the base refreshes it only after the step is taken.)
    fa_.resize(ya_.size());
    f(ta_, ya_, fa_);
    // A right-hand side that changed without a restart (switches not located) is refused, not
    // integrated in the old mode.
    if (const Index i = mismatch(*seg_, ya_, fa_); i >= 0)
      refuse(
          fmt::format("the right-hand side changed between restarts at t = {:.17g} (entry {}); it needs a "
                      "restart at every switch (located switches)",
                      ta_, i));
    gather(fa_, p_, fp_);
    double h = t_limit - ta_;
    if (max_step_ > 0) h = std::min(h, max_step_);
    if (seg_->rho > 0) h = std::min(h, 1.0 / seg_->rho);
    const double size = std::max(max_abs_at(ya_, p_), 1e-300);
    // Terms b_j = (h A)^(j-1) h f / j!, in the step's fraction s = (t - ta) / h: y(t) = y_a + sum b_j s^j.
    for (int tries = 0;; ++tries) {
      B_.resize(static_cast<Index>(p_.size()), kMaxTerms);
      b_ = h * fp_;
      terms_ = 0;
      bool converged = false;
      double last = std::numeric_limits<double>::infinity();
      for (int j = 1; j <= kMaxTerms; ++j) {
        const double norm = max_abs(b_);
        if (!std::isfinite(norm)) break;  // overflowed: rho underestimated the growth
        if (norm == 0) {                  // the series ended: exact
          converged = true;
          break;
        }
        B_.col(terms_++) = b_;
        const double floor = 0.25 * kEps * std::max(size, max_abs(B_.col(0)));
        if (norm <= floor && last <= floor) {
          converged = true;
          break;
        }
        last = norm;
        tmp_.noalias() = seg_->A * b_;
        b_ = (h / (j + 1)) * tmp_;
      }
      if (converged) break;
      if (tries > 60) refuse(fmt::format("its Taylor series did not converge at t = {:.17g}", ta_));
      h *= 0.5;  // rho underestimated the growth: a shorter step
    }
    h_ = h;
    collect_polynomial();
    tb_ = h == t_limit - ta_ ? t_limit : ta_ + h;
    yb_.resize(ya_.size());
    dense(tb_, yb_);
  }

  // The whole state along the step as one polynomial in s = (t - ta) / h, a column per power:
  // the affine entries' Taylor terms, and each quadrature's integral h sum a_n s^(n+1) / (n + 1)
  // of its integrand a_0 = f_q(y_a), a_n = g_a . b_n + sum over i + j = n of b_i' H b_j (g_a the
  // gradient at the step's start), cut where its terms fall below rounding.
  void collect_polynomial() {
    const Index n = ya_.size(), m = static_cast<Index>(p_.size()), r = static_cast<Index>(q_.size());
    Index degree = terms_;
    if (r > 0) {
      Aq_.setZero(r, 2 * terms_ + 1);
      offset_from(*seg_, ya_);
      for (Index s = 0; s < r; ++s) {
        const Matrix& H = seg_->H[static_cast<std::size_t>(s)];
        hu_.noalias() = H * u_;
        g_ = seg_->G.row(s).transpose() + 2 * hu_;
        HB_.noalias() = H * B_.leftCols(terms_);
        Aq_(s, 0) = fa_[q_[static_cast<std::size_t>(s)]];
        // Plain loops: the vectors are a few entries long, below what Eigen's kernels pay off for.
        for (Index i = 0; i < terms_; ++i) {
          const double* bi = B_.col(i).data();
          double gb = 0;
          for (Index k = 0; k < m; ++k) gb += g_[k] * bi[k];
          Aq_(s, i + 1) += gb;
          for (Index j = 0; j < terms_; ++j) {
            const double* hj = HB_.col(j).data();
            double bhb = 0;
            for (Index k = 0; k < m; ++k) bhb += bi[k] * hj[k];
            Aq_(s, i + j + 2) += bhb;
          }
        }
        for (Index k = 0; k <= 2 * terms_; ++k) Aq_(s, k) *= h_ / static_cast<double>(k + 1);
      }
      // The last power whose term is not below rounding of the quadrature's value.
      Index used = 2 * terms_ + 1;
      const double scale = std::max(max_abs_at(ya_, q_), Aq_.cwiseAbs().maxCoeff());
      while (used > 1 && Aq_.col(used - 1).cwiseAbs().maxCoeff() <= 0.25 * kEps * scale) --used;
      degree = std::max(degree, used);
    }
    C_.setZero(n, degree + 1);
    C_.col(0) = ya_;
    for (Index j = 0; j < terms_; ++j)
      for (Index k = 0; k < m; ++k) C_(p_[static_cast<std::size_t>(k)], j + 1) = B_(k, j);
    for (Index s = 0; s < r; ++s)
      for (Index k = 0; k + 1 <= degree && k < Aq_.cols(); ++k)
        C_(q_[static_cast<std::size_t>(s)], k + 1) = Aq_(s, k);
  }

  void dense(double t, VectorRef y) override {
    if (!(t > ta_)) {
      y = ya_;
      return;
    }
    // Horner's rule per entry, in plain loops: a few entries, called ~20 times per step.
    const double s = (t - ta_) / h_;
    const Index n = C_.rows(), top = C_.cols() - 1;
    for (Index i = 0; i < n; ++i) {
      double value = C_(i, top);
      for (Index k = top; k-- > 0;) value = value * s + C_(i, k);
      y[i] = value;
    }
  }

  bool dense_is_interpolant() const override { return true; }
  // A step is at most 1 / rho, a sixth of the fastest period, as short against the oscillation as
  // an RK8 step at rtol 1e-6, and its roots are looked at in eight parts (root_scan_parts). A free
  // flight (rho = 0) is one step however long: a body under gravity follows a parabola, which the
  // base's cubic Hermite check reproduces, so only a polynomial of higher degree is checked.
  bool steps_may_cross_twice() const override { return seg_ && seg_->rho == 0 && terms_ > 3; }
  double negligible_size() const override { return atol_; }
  // Its dense output is the exact solution, a polynomial: the roots are looked at in eight parts of
  // every step, so a switch that grazes zero within one (a slow contact's exit, the overlap closing
  // and, in the held mode, opening again a few milliseconds later) is not stepped over (ball drop,
  // k = 3836 N/m: the eighth contact's exit was, E + D off by 4e-5 E0).
  int root_scan_parts() const override { return 8; }

  double max_step_, atol_;
  std::vector<Index> p_, q_;  // the affine entries and the quadratures
  std::vector<Segment> kept_;
  const Segment* seg_ = nullptr;  // the current one, in kept_
  SparseMatrix J_;
  Matrix Jd_;
  Matrix B_, Aq_, HB_, C_;  // the step's Taylor terms, quadrature integrals, the whole polynomial
  Vector fa_, fp_, b_, tmp_, u_, w_, g_, hu_;
  Index terms_ = 0;
  double h_ = 0;
  long jac_evals_ = 0;
};

}  // namespace

std::unique_ptr<Integrator> make_exact_linear(const IntegratorOptions& o, OdeSystem system, double t0,
                                              ConstVectorRef y0) {
  return std::make_unique<ExactLinearIntegrator>(o, std::move(system), t0, y0);
}

}  // namespace contact
