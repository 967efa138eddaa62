#include "ccal/model/first_order.hpp"

#include <array>
#include <cmath>
#include <numbers>

namespace ccal {

namespace {

constexpr double kHalfPi = std::numbers::pi / 2;
using V3 = Eigen::Vector3d;

// Parent frame of a link and the pivot of its error rotation (the parent origin moved by the link's nominal
// translation), both on the error-free chain.
struct LinkFrames {
  FrameMotion<double> parent;
  FrameMotion<double> pivot;
};

struct NominalChain {
  std::array<LinkFrames, 8> links;  // indexed by Link (drive excluded)
  FrameMotion<double> instrument;
};

NominalChain nominal_chain(const Geometry& geo, const JointState<double>& j) {
  NominalChain n;
  FrameMotion<double> m;
  auto record = [&](Link link, const V3& nominal_translation) {
    auto& lf = n.links[static_cast<int>(link)];
    lf.parent = m;
    m.translate(nominal_translation);
    lf.pivot = m;
  };
  const V3 zero = V3::Zero();
  record(Link::main_sleeve, zero);
  record(Link::main_axis, zero);
  m.rotate(2, j.theta1, j.theta1_rate, 0.0);
  record(Link::horizontal_sleeve, V3(geo.R0, 0, 0));
  record(Link::horizontal_axis, zero);
  m.rotate(0, j.beta, j.beta_rate, 0.0);
  record(Link::azimuth_sleeve, zero);
  record(Link::azimuth_axis, zero);
  m.rotate(2, j.gamma, j.gamma_rate, 0.0);
  record(Link::base_plane, V3(0, 0, geo.L));
  record(Link::instrument, V3(0, 0, geo.l));
  n.instrument = m;
  return n;
}

// Unit-amplitude time function of a parameter: 1 for a static error, cos kq or sin kq for a harmonic
// coefficient of a dynamic one, with its time derivatives.
ChannelValue<double> basis(const ErrorLayout& layout, int index, const JointState<double>& j) {
  const Channel& ch = channels()[layout.parameter_channel(index)];
  if (ch.joint == Joint::none) return {1.0, 0.0, 0.0};
  const double q = ch.joint == Joint::main ? j.theta1 : ch.joint == Joint::horizontal ? j.beta : j.gamma;
  const double qd = ch.joint == Joint::main         ? j.theta1_rate
                    : ch.joint == Joint::horizontal ? j.beta_rate
                                                    : j.gamma_rate;
  const int k = layout.parameter_harmonic(index);
  const bool sine = layout.parameter_is_sine(index);
  const double c = std::cos(k * q), s = std::sin(k * q);
  const double value = sine ? s : c;
  const double slope = sine ? k * c : -k * s;
  return {value, qd * slope, -qd * qd * k * k * value};
}

int axis_of(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::rotation_x:
    case ErrorKind::translation_x:
    case ErrorKind::arm_stretch:
      return 0;
    case ErrorKind::rotation_y:
    case ErrorKind::translation_y:
      return 1;
    default:
      return 2;
  }
}

bool is_rotation(ErrorKind kind) {
  return kind == ErrorKind::rotation_x || kind == ErrorKind::rotation_y || kind == ErrorKind::rotation_z;
}

}  // namespace

FirstOrderResult exact_first_order(const Geometry& geo, const ErrorLayout& layout, const Site& site,
                                   const RunMotion<double>& run, PlatformMode mode, double t) {
  const JointState<double> j = run.at(t);
  const NominalChain chain = nominal_chain(geo, j);
  const FrameMotion<double>& five = chain.instrument;
  const V3 earth = site.coriolis_rate_enu();  // in the Coriolis force
  const V3 sensed = site.sensed_rate_enu();   // in the instrument's rate
  const double g = site.g;
  const V3 f = five.a + 2.0 * earth.cross(five.v) + V3(0, 0, g);
  const V3 w_inertial = five.w + sensed;
  const Eigen::Matrix3d RT = five.R.transpose();

  FirstOrderResult out;
  out.nominal << RT * f / g, RT * w_inertial;
  out.sensitivity = SensitivityMatrix::Zero(6, layout.size());

  for (int index = 0; index < layout.size(); ++index) {
    const Channel& ch = channels()[layout.parameter_channel(index)];
    if (ch.link == Link::drive) continue;  // below
    const LinkFrames& lf = chain.links[static_cast<int>(ch.link)];
    const FrameMotion<double>& P = lf.parent;
    ChannelValue<double> b = basis(layout, index, j);
    if (ch.kind == ErrorKind::arm_stretch) b = {j.theta1_rate * j.theta1_rate, 0.0, 0.0};
    const V3 n = P.R.col(axis_of(ch.kind));
    const V3 X = n * b.value;
    const V3 Xd = P.w.cross(X) + n * b.rate;
    const V3 Xdd = P.dw.cross(X) + P.w.cross(Xd) + P.w.cross(n * b.rate) + n * b.acc;
    V3 df, dw;
    if (is_rotation(ch.kind)) {
      const V3 l = five.p - lf.pivot.p, ld = five.v - lf.pivot.v, ldd = five.a - lf.pivot.a;
      const V3 drdd = Xdd.cross(l) + 2.0 * Xd.cross(ld) + X.cross(ldd);
      const V3 drd = Xd.cross(l) + X.cross(ld);
      df = drdd + 2.0 * earth.cross(drd) - X.cross(f);
      dw = n * b.rate + X.cross(five.w - P.w) - X.cross(w_inertial);
    } else {
      df = Xdd + 2.0 * earth.cross(Xd);
      dw = V3::Zero();
    }
    out.sensitivity.col(index) << RT * df / g, RT * dw;
  }

  // Drive errors. With β = 0 the error-free instrument sits on the azimuth axis at r = R0 e(θ1) + (L+l) z,
  // e(α) = (cos α, sin α, 0): v = θ̇1 R0 e(θ1+π/2), a = −θ̇1² R0 e(θ1), axes IA = e(ψ), PA = e(ψ+π/2),
  // OA = z with ψ = θ1 + γ, and ω₀₅ = (θ̇1 + γ̇) z. Δω changes θ̇1 by 1, θ1(t) by t and, on a counter-rotating
  // platform, γ̇ by −1 and γ(t) by −t; ΔΩ changes γ̇ by −1 and γ(t) by −t there, nothing on a fixed one.
  auto e = [](double a) { return V3(std::cos(a), std::sin(a), 0.0); };
  const double R0 = geo.R0, wr = j.theta1_rate, psi = j.theta1 + j.gamma;
  const V3 ez(0, 0, 1);
  auto outputs = [&](const V3& force, const V3& rate, double p) {
    Eigen::Matrix<double, 6, 1> y;
    y << e(p).dot(force) / g, e(p + kHalfPi).dot(force) / g, force.z() / g, e(p).dot(rate),
        e(p + kHalfPi).dot(rate), rate.z();
    return y;
  };
  // ∂/∂θ1 and ∂/∂θ̇1 of the force at fixed ψ; ∂/∂ψ of the projections at fixed vectors.
  const V3 a = -wr * wr * R0 * e(j.theta1), v = wr * R0 * e(j.theta1 + kHalfPi);
  const V3 force = a + 2.0 * earth.cross(v) + g * ez;
  const V3 force_theta1 = -wr * wr * R0 * e(j.theta1 + kHalfPi) + 2.0 * earth.cross(-wr * R0 * e(j.theta1));
  const V3 force_rate = -2.0 * wr * R0 * e(j.theta1) + 2.0 * earth.cross(R0 * e(j.theta1 + kHalfPi));
  const V3 rate = five.w + sensed;
  Eigen::Matrix<double, 6, 1> d_psi;
  d_psi << e(psi + kHalfPi).dot(force) / g, -e(psi).dot(force) / g, 0.0, e(psi + kHalfPi).dot(rate),
      -e(psi).dot(rate), 0.0;
  Eigen::Matrix<double, 6, 1> d_theta1 = outputs(force_theta1, V3::Zero(), psi);
  Eigen::Matrix<double, 6, 1> d_theta1_rate = outputs(force_rate, ez, psi);
  Eigen::Matrix<double, 6, 1> d_gamma_rate;
  d_gamma_rate << 0, 0, 0, 0, 0, 1;
  const bool counter = mode == PlatformMode::counter_rotating;
  Eigen::Matrix<double, 6, 1> d_domega = d_theta1_rate + t * (d_theta1 + d_psi);
  Eigen::Matrix<double, 6, 1> d_dOmega = Eigen::Matrix<double, 6, 1>::Zero();
  if (counter) {
    d_domega += -d_gamma_rate - t * d_psi;
    d_dOmega = -d_gamma_rate - t * d_psi;
  }
  // The drives' rate ripple (model.md §3.1): a unit coefficient of harmonic k moves the main axis by
  // δ(q) = sin kq / k (cosine term) or −cos kq / k (sine term), its rate by q̇ r(q) and its acceleration by
  // q̇² r′(q). The platform keeps γ (speed control: ψ moves with θ1) or follows the main axis (phase-locked:
  // γ moves by −δ, ψ stays). A platform ripple moves γ and γ̇ alone. With the instrument on the azimuth axis
  // (β = 0) γ̈ moves nothing; θ̈1 adds the tangential R0 θ̈1 e(θ1 + π/2).
  Eigen::Matrix<double, 6, 1> d_theta1_acc = outputs(R0 * e(j.theta1 + kHalfPi), V3::Zero(), psi);
  const bool follows = counter && geo.platform_control == PlatformControl::phase_locked;
  auto ripple_column = [&](int index) {
    const int channel = layout.parameter_channel(index);
    const int k = layout.parameter_harmonic(index);
    Eigen::Matrix<double, 6, 1> column = Eigen::Matrix<double, 6, 1>::Zero();
    if (k == 0 || (channel == ripple3 && !counter)) return column;
    const bool sine = layout.parameter_is_sine(index);
    const double q = channel == ripple1 ? j.theta1 : j.gamma;
    const double q_rate = channel == ripple1 ? wr : j.gamma_rate;
    const double c = std::cos(k * q), s = std::sin(k * q);
    const double angle = sine ? -c / k : s / k, relative = sine ? s : c, slope = sine ? k * c : -k * s;
    if (channel == ripple3)
      return Eigen::Matrix<double, 6, 1>(angle * d_psi + q_rate * relative * d_gamma_rate);
    column = angle * (follows ? d_theta1 : Eigen::Matrix<double, 6, 1>(d_theta1 + d_psi)) +
             q_rate * relative * d_theta1_rate + q_rate * q_rate * slope * d_theta1_acc;
    if (follows) column -= q_rate * relative * d_gamma_rate;
    return column;
  };
  std::vector<int> drive_parameters{int(domega), int(dOmega)};
  for (int channel : {int(ripple1), int(ripple3)})
    for (int k = 1; k <= layout.harmonic_order(); ++k)
      for (bool sine : {false, true}) drive_parameters.push_back(layout.harmonic_index(channel, k, sine));
  if (geo.beta == 0.0) {
    out.sensitivity.col(layout.static_index(domega)) = d_domega;
    out.sensitivity.col(layout.static_index(dOmega)) = d_dOmega;
    for (std::size_t i = 2; i < drive_parameters.size(); ++i)
      out.sensitivity.col(drive_parameters[i]) = ripple_column(drive_parameters[i]);
  } else {
    // No closed form is kept for a tilted horizontal axis: central differences of the exact chain, step
    // 1e-7 (rad/s for the rates, relative for the ripple; error O(h²·∂³) ≈ 1e-14 relative on outputs that are
    // quadratic in the rates).
    const double h = 1e-7;
    for (int index : drive_parameters) {
      Eigen::VectorXd ep = Eigen::VectorXd::Zero(layout.size()), em = ep;
      ep[index] = h;
      em[index] = -h;
      auto eval = [&](const Eigen::VectorXd& err) {
        RunMotion<double> r = run;
        r.theta1_rate += err[domega];
        if (counter) r.gamma_rate -= err[domega] + err[dOmega];
        const RunMotion<double> rippled = run_motion<double>(0.0, 0.0, 0.0, mode, geo, layout, err);
        r.main_ripple = rippled.main_ripple;
        r.platform_ripple = rippled.platform_ripple;
        r.platform_follows_main = rippled.platform_follows_main;
        const auto s = exact_state<double>(geo, layout, err, site, r.at(t));
        Eigen::Matrix<double, 6, 1> y;
        y << s.specific_force, s.angular_rate;
        return y;
      };
      out.sensitivity.col(index) = (eval(ep) - eval(em)) / (2 * h);
    }
  }
  return out;
}

FirstOrderResult paper_first_order(const Geometry& geo, const ErrorLayout& layout, const Site& site,
                                   const JointState<double>& j, const PaperFormOptions& options) {
  const double R0 = geo.R0, A = R0 * j.theta1_rate * j.theta1_rate / site.g;
  const double cg = std::cos(j.gamma), sg = std::sin(j.gamma);
  const double h = options.lever_arms ? geo.L + geo.l : 0.0;
  const double l = options.lever_arms ? geo.l : 0.0;
  const double Omega = j.theta1_rate;
  const double coriolis = 2.0 * site.earth_rate * (site.earth_rotation && site.apply_coriolis ? 1.0 : 0.0) *
                          R0 * Omega * std::sin(site.latitude) / site.g;

  FirstOrderResult out;
  out.sensitivity = SensitivityMatrix::Zero(6, layout.size());
  // Nominal: a_i = −A cos γ − Coriolis (constant or × cos γ); ω_IA = Earth rate on the IA azimuth.
  const double psi = j.theta1 + j.gamma;
  const Eigen::Vector3d earth = site.sensed_rate_enu();
  out.nominal.setZero();
  out.nominal[0] = -A * cg - coriolis * (options.constant_coriolis ? 1.0 : cg);
  out.nominal[3] = std::cos(psi) * earth.x() + std::sin(psi) * earth.y();

  for (int index = 0; index < layout.size(); ++index) {
    const int channel = layout.parameter_channel(index);
    const ChannelValue<double> b = basis(layout, index, j);
    const double v = b.value;
    double dai = 0.0, dwi = 0.0;
    switch (channel) {
      // θx group: a_i ∋ +(1 + A(L+l)/R0) θx sin γ;  ω_IA ∋ +Ω θx sin γ.
      case dthx3t:
      case dthx3:
        dai = (1.0 + A * h / R0) * sg * v;
        dwi = Omega * sg * v;
        break;
      // θy group: a_i ∋ −(1 + A(L+l)/R0) θy cos γ;  ω_IA ∋ −Ω θy cos γ.
      case dthy2t:
      case dthy2:
      case dthy3t:
      case dthy3:
        dai = -(1.0 + A * h / R0) * cg * v;
        dwi = -Omega * cg * v;
        break;
      case dy2t:
      case dy2:
      case dy3t:
      case dy3:
        dai = -A / R0 * sg * v;
        break;
      case dthz5:
      case dthz2:
        dai = A * sg * v;
        break;
      case dR_s:
      case dx2:
      case dx3:
        dai = -A / R0 * cg * v;
        break;
      case arm_stretch:
        dai = -A / R0 * cg * Omega * Omega;
        break;
      case dx5:
        dai = -A / R0;
        break;
      case dthy4:
        dai = -1.0 - A * l / R0;
        break;
      case dthy5:
        dai = -1.0;
        break;
      case domega:
        dai = -2.0 * A / Omega * cg;
        break;  // amplitude only: A ∝ (Ω+Δω)² (Eq.19)
      default:
        break;  // not in the paper's Eq.(14)
    }
    out.sensitivity(0, index) = dai;
    out.sensitivity(3, index) = dwi;
  }
  return out;
}

}  // namespace ccal
