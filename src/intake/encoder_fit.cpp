#include "ccal/intake/encoder_fit.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace ccal {

EncoderFit::EncoderFit(int harmonic_order, double max_turn)
    : order_(std::max(harmonic_order, 0)),
      p_(std::size_t(2 + 2 * order_)),
      first_harmonic_(max_turn),
      normal_(p_ * p_, 0.0),
      rhs_(p_, 0.0),
      x_(p_, 0.0) {
  buffer_.reserve(3 * kReferenceSamples);
}

void EncoderFit::buffer(double tau, double angle, double reading) {
  buffer_.insert(buffer_.end(), {tau, angle, reading});
  if (buffer_.size() == 3 * kReferenceSamples) set_reference();
}

// The centred least-squares line of the buffered samples (two passes over a bounded buffer), then the
// buffered samples accumulated against it.
void EncoderFit::set_reference() {
  const std::size_t m = buffer_.size() / 3;
  double tm = 0, am = 0;
  for (std::size_t i = 0; i < m; ++i) {
    tm += buffer_[3 * i];
    am += buffer_[3 * i + 1];
  }
  tm /= double(m);
  am /= double(m);
  double stt = 0, sta = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const double dt = buffer_[3 * i] - tm;
    stt += dt * dt;
    sta += dt * (buffer_[3 * i + 1] - am);
  }
  ref_slope_ = stt > 0 ? sta / stt : 0.0;
  ref_start_ = am - ref_slope_ * tm;
  referenced_ = true;
  for (std::size_t i = 0; i < m; ++i) push(buffer_[3 * i], buffer_[3 * i + 1], buffer_[3 * i + 2]);
  buffer_.clear();
  buffer_.shrink_to_fit();
}

// Regressors 1, τ, cos kα, sin kα (k = 1..N, from the reading: k = 1 turned from an earlier reading,
// sincos_track.hpp; the multiples by the angle-addition recurrence) and the angle less the reference line;
// the upper triangle of XᵀX, Xᵀd and Σd².
void EncoderFit::accumulate_batch() {
  const std::size_t n = batch_size_;
  if (n == 0) return;
  if (order_ > 0) first_harmonic_.next(batch_reading_, batch_cos_, batch_sin_, n);
  if (order_ == 1)
    accumulate_first_harmonic(n);
  else
    accumulate_products(n);
  last_tau_ = batch_tau_[n - 1];
  n_ += n;
  batch_size_ = 0;
}

// Any order: the sums in memory, the regressors of one sample at a time in x_.
void EncoderFit::accumulate_products(std::size_t n) {
  const std::size_t p = p_;
  double* a = normal_.data();
  double* b = rhs_.data();
  double* x = x_.data();
  for (std::size_t k = 0; k < n; ++k) {
    const double tau = batch_tau_[k];
    const double d = batch_angle_[k] - (ref_start_ + ref_slope_ * tau);
    x[0] = 1.0;
    x[1] = tau;
    if (order_ > 0) {
      const double c1 = batch_cos_[k], s1 = batch_sin_[k];
      double c = c1, s = s1;
      for (int h = 1; h <= order_; ++h) {
        x[2 * h] = c;
        x[2 * h + 1] = s;
        const double next = c * c1 - s * s1;
        s = s * c1 + c * s1;
        c = next;
      }
    }
    for (std::size_t i = 0; i < p; ++i) {
      const double xi = x[i];
      for (std::size_t j = i; j < p; ++j) a[i * p + j] += xi * x[j];
      b[i] += xi * d;
    }
    dd_ += d * d;
  }
}

// Order 1, the usual one: regressors 1, τ, c, s and the fifteen sums as named locals, which stay in
// registers over the batch. The same sums as accumulate_products (1·v is v exactly).
void EncoderFit::accumulate_first_harmonic(std::size_t n) {
  double* a = normal_.data();  // 4×4 row-major
  double s00 = a[0], s01 = a[1], s02 = a[2], s03 = a[3], s11 = a[5], s12 = a[6], s13 = a[7], s22 = a[10],
         s23 = a[11], s33 = a[15];
  double b0 = rhs_[0], b1 = rhs_[1], b2 = rhs_[2], b3 = rhs_[3], dd = dd_;
  for (std::size_t k = 0; k < n; ++k) {
    const double tau = batch_tau_[k];
    const double d = batch_angle_[k] - (ref_start_ + ref_slope_ * tau);
    const double c = batch_cos_[k], s = batch_sin_[k];
    s00 += 1.0;
    s01 += tau;
    s02 += c;
    s03 += s;
    s11 += tau * tau;
    s12 += tau * c;
    s13 += tau * s;
    s22 += c * c;
    s23 += c * s;
    s33 += s * s;
    b0 += d;
    b1 += tau * d;
    b2 += c * d;
    b3 += s * d;
    dd += d * d;
  }
  a[0] = s00, a[1] = s01, a[2] = s02, a[3] = s03, a[5] = s11, a[6] = s12, a[7] = s13, a[10] = s22,
  a[11] = s23, a[15] = s33;
  rhs_[0] = b0, rhs_[1] = b1, rhs_[2] = b2, rhs_[3] = b3;
  dd_ = dd;
}

namespace {

struct Solution {
  Eigen::VectorXd beta;
  Eigen::MatrixXd inverse;  // (XᵀX)⁻¹
  bool ok = false;
};

// The normal equations' leading m×m block solved with Jacobi scaling (the columns 1 and τ differ in size by
// the run's length), by LDLᵀ; refused when not finite or near-singular.
Solution solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, Eigen::Index m) {
  Solution s;
  const Eigen::MatrixXd block = a.topLeftCorner(m, m);
  if (!(block.diagonal().array() > 0).all()) return s;
  const Eigen::VectorXd scale = block.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = scale.asDiagonal() * block * scale.asDiagonal();
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(scaled);
  if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-12)) return s;
  s.beta = scale.asDiagonal() * ldlt.solve(scale.asDiagonal() * b.head(m));
  s.inverse = scale.asDiagonal() * ldlt.solve(Eigen::MatrixXd::Identity(m, m)) * scale.asDiagonal();
  s.ok = s.beta.allFinite() && s.inverse.allFinite();
  return s;
}

}  // namespace

EncoderFitResult EncoderFit::result() {
  if (!referenced_) set_reference();
  accumulate_batch();
  const auto p = Eigen::Index(p_);
  Eigen::MatrixXd a(p, p);
  Eigen::VectorXd b(p);
  for (Eigen::Index i = 0; i < p; ++i) {
    b[i] = rhs_[std::size_t(i)];
    for (Eigen::Index j = i; j < p; ++j) a(i, j) = a(j, i) = normal_[std::size_t(i * p + j)];
  }
  EncoderFitResult r;
  r.samples = n_;
  Solution s = solve(a, b, 2);
  if (!s.ok) {  // a single sample, or times too close to tell apart: the reference line alone
    s.beta = Eigen::VectorXd::Zero(2);
    s.inverse = Eigen::MatrixXd::Zero(2, 2);
  }
  // Harmonics only over at least a revolution and with enough samples to average the noise: below that the
  // cos kα, sin kα are nearly constant or linear in τ and the solution would trade them for the line.
  const double travel = std::abs(ref_slope_ + s.beta[1]) * last_tau_;
  if (order_ > 0 && n_ >= 4 * p_ && travel >= 2 * std::numbers::pi) {
    Solution full = solve(a, b, p);
    if (full.ok) s = std::move(full);
  }
  r.slope = ref_slope_ + s.beta[1];
  r.start = ref_start_ + s.beta[0];
  r.end = r.start + r.slope * last_tau_;
  const Eigen::Index m = s.beta.size();
  const double rss = std::max(0.0, dd_ - s.beta.dot(b.head(m)));
  r.rms = std::sqrt(rss / double(n_));
  if (m > 2) {
    r.harmonics.assign(s.beta.data() + 2, s.beta.data() + m);
    const double variance = n_ > std::size_t(m) ? rss / double(n_ - std::size_t(m)) : 0.0;
    r.harmonic_sigma = std::sqrt(variance * s.inverse.diagonal().tail(m - 2).maxCoeff());
  }
  return r;
}

}  // namespace ccal
