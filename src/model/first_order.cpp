#include "ccal/model/first_order.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

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
// cos kq and sin kq of the joints' angles q at one node, each pair computed once (a channel's cos and sin
// coefficients, and every channel on the same joint, share them; the same calls as before, so the same bits).
class JointTrig {
 public:
  explicit JointTrig(const JointState<double>& j) : j_(j) {}
  void of(Joint joint, int k, double& c, double& s) {
    Entry& e = memo_[std::size_t(joint)][std::size_t(k)];
    if (!e.set) {
      const double q = joint == Joint::main ? j_.theta1 : joint == Joint::horizontal ? j_.beta : j_.gamma;
      e = {std::cos(k * q), std::sin(k * q), true};
    }
    c = e.c;
    s = e.s;
  }

 private:
  struct Entry {
    double c = 0, s = 0;
    bool set = false;
  };
  const JointState<double>& j_;
  std::array<std::array<Entry, kMaxHarmonicOrder + 1>, 4> memo_{};  // [joint][k]
};

ChannelValue<double> basis(const ErrorLayout& layout, int index, const JointState<double>& j,
                           JointTrig& trig) {
  const Channel& ch = channels()[layout.parameter_channel(index)];
  if (ch.joint == Joint::none) return {1.0, 0.0, 0.0};
  const double qd = ch.joint == Joint::main         ? j.theta1_rate
                    : ch.joint == Joint::horizontal ? j.beta_rate
                                                    : j.gamma_rate;
  const int k = layout.parameter_harmonic(index);
  const bool sine = layout.parameter_is_sine(index);
  double c, s;
  trig.of(ch.joint, k, c, s);
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

using Column = Eigen::Matrix<double, 6, 1>;  // (f_IA, f_PA, f_OA [g], ω_IA, ω_PA, ω_OA [rad/s])

// The error-free instrument the sensitivities are taken about: frame 5 of the chain, the specific force
// f = a + 2 ω_c × v + g ẑ and the inertial rate ω + ω_ie (world coordinates), and R₅ᵀ.
struct NominalInstrument {
  const FrameMotion<double>& five;
  V3 earth;   // in the Coriolis force
  V3 sensed;  // in the instrument's rate
  double g;     // gravity [m/s²]
  double unit;  // the g of the g-levels [m/s²]
  V3 f;
  V3 w_inertial;
  Eigen::Matrix3d RT;
};

NominalInstrument nominal_instrument(const FrameMotion<double>& five, const Site& site) {
  const V3 earth = site.coriolis_rate_enu();
  const V3 sensed = site.sensed_rate_enu();
  const double g = site.g;
  const V3 f = five.a + 2.0 * earth.cross(five.v) + V3(0, 0, g);
  const V3 w_inertial = five.w + sensed;
  return {five, earth, sensed, g, site.g_unit(), f, w_inertial, five.R.transpose()};
}

// The column of one link error (not a drive) by small-twist perturbation (first_order.hpp, model.md §5.2):
// X = R_P n b(t) with its derivatives Ẋ = ω_P × X + R_P n ḃ, Ẍ = ω̇_P × X + ω_P × Ẋ + ω_P × (R_P n ḃ) + R_P n
// b̈; a rotation turns the instrument about the link's pivot, δr̈ = Ẍ × ℓ + 2 Ẋ × ℓ̇ + X × ℓ̈, δṙ = Ẋ × ℓ + X ×
// ℓ̇,
//     δf = δr̈ + 2 ω_c × δṙ − X × f,   δω = R_P n ḃ + X × (ω₅ − ω_P) − X × ω₅ⁱ;
// a translation moves it: δf = Ẍ + 2 ω_c × Ẋ, δω = 0. Both taken into frame 5 (f over g).
Column link_error_column(const LinkFrames& lf, const NominalInstrument& nom, ErrorKind kind,
                         const ChannelValue<double>& b) {
  const FrameMotion<double>& P = lf.parent;
  const FrameMotion<double>& five = nom.five;
  const V3 n = P.R.col(axis_of(kind));
  const V3 X = n * b.value;
  const V3 Xd = P.w.cross(X) + n * b.rate;
  const V3 Xdd = P.dw.cross(X) + P.w.cross(Xd) + P.w.cross(n * b.rate) + n * b.acc;
  V3 df, dw;
  if (is_rotation(kind)) {
    const V3 l = five.p - lf.pivot.p, ld = five.v - lf.pivot.v, ldd = five.a - lf.pivot.a;
    const V3 drdd = Xdd.cross(l) + 2.0 * Xd.cross(ld) + X.cross(ldd);
    const V3 drd = Xd.cross(l) + X.cross(ld);
    df = drdd + 2.0 * nom.earth.cross(drd) - X.cross(nom.f);
    dw = n * b.rate + X.cross(five.w - P.w) - X.cross(nom.w_inertial);
  } else {
    df = Xdd + 2.0 * nom.earth.cross(Xd);
    dw = V3::Zero();
  }
  Column column;
  column << nom.RT * df / nom.unit, nom.RT * dw;
  return column;
}

// The outputs' derivatives in the drives' joint variables with β = 0, where the error-free instrument sits on
// the azimuth axis at r = R0 e(θ1) + (L+l) z, e(α) = (cos α, sin α, 0): v = θ̇1 R0 e(θ1+π/2),
// a = −θ̇1² R0 e(θ1), axes IA = e(ψ), PA = e(ψ+π/2), OA = z with ψ = θ1 + γ, and ω₀₅ = (θ̇1 + γ̇) z.
// ∂/∂θ1 and ∂/∂θ̇1 of the force at fixed ψ; ∂/∂ψ of the projections at fixed vectors; ∂/∂γ̇ moves the OA rate
// alone; θ̈1 adds the tangential R0 θ̈1 e(θ1 + π/2) (γ̈ moves nothing).
struct DriveDerivatives {
  Column d_psi, d_theta1, d_theta1_rate, d_gamma_rate, d_theta1_acc;
};

DriveDerivatives drive_derivatives(const Geometry& geo, const JointState<double>& j,
                                   const NominalInstrument& nom) {
  auto e = [](double a) { return V3(std::cos(a), std::sin(a), 0.0); };
  const double R0 = geo.R0, wr = j.theta1_rate, psi = j.theta1 + j.gamma, g = nom.g, unit = nom.unit;
  // The four directions, each evaluated once (the cos and sin calls are most of this function's time).
  const V3 e_theta1 = e(j.theta1), e_theta1_normal = e(j.theta1 + kHalfPi), e_psi = e(psi),
           e_psi_normal = e(psi + kHalfPi);
  const V3& earth = nom.earth;
  const V3 ez(0, 0, 1);
  auto outputs = [&](const V3& force, const V3& rate) {
    Column y;
    y << e_psi.dot(force) / unit, e_psi_normal.dot(force) / unit, force.z() / unit, e_psi.dot(rate),
        e_psi_normal.dot(rate), rate.z();
    return y;
  };
  const V3 a = -wr * wr * R0 * e_theta1, v = wr * R0 * e_theta1_normal;
  const V3 force = a + 2.0 * earth.cross(v) + g * ez;
  const V3 force_theta1 = -wr * wr * R0 * e_theta1_normal + 2.0 * earth.cross(-wr * R0 * e_theta1);
  const V3 force_rate = -2.0 * wr * R0 * e_theta1 + 2.0 * earth.cross(R0 * e_theta1_normal);
  const V3 rate = nom.five.w + nom.sensed;
  DriveDerivatives D;
  D.d_psi << e_psi_normal.dot(force) / unit, -e_psi.dot(force) / unit, 0.0, e_psi_normal.dot(rate),
      -e_psi.dot(rate), 0.0;
  D.d_theta1 = outputs(force_theta1, V3::Zero());
  D.d_theta1_rate = outputs(force_rate, ez);
  D.d_gamma_rate << 0, 0, 0, 0, 0, 1;
  D.d_theta1_acc = outputs(R0 * e_theta1_normal, V3::Zero());
  return D;
}

// The column of a harmonic coefficient of the drives' rate ripple (model.md §3.1) with β = 0: a unit
// coefficient of harmonic k moves the main axis by δ(q) = sin kq / k (cosine term) or −cos kq / k (sine
// term), its rate by q̇ r(q) and its acceleration by q̇² r′(q). The platform keeps γ (speed control: ψ moves
// with θ1) or follows the main axis (phase-locked: γ moves by −δ, ψ stays). A platform ripple moves γ and γ̇
// alone (nothing on a fixed platform).
Column ripple_column(const ErrorLayout& layout, int index, const JointState<double>& j,
                     const DriveDerivatives& D, bool counter, bool follows) {
  const int channel = layout.parameter_channel(index);
  const int k = layout.parameter_harmonic(index);
  Column column = Column::Zero();
  if (k == 0 || (channel == ch::ripple3 && !counter)) return column;
  const bool sine = layout.parameter_is_sine(index);
  const double q = channel == ch::ripple1 ? j.theta1 : j.gamma;
  const double q_rate = channel == ch::ripple1 ? j.theta1_rate : j.gamma_rate;
  const double c = std::cos(k * q), s = std::sin(k * q);
  const double angle = sine ? -c / k : s / k, relative = sine ? s : c, slope = sine ? k * c : -k * s;
  if (channel == ch::ripple3) return Column(angle * D.d_psi + q_rate * relative * D.d_gamma_rate);
  column = angle * (follows ? D.d_theta1 : Column(D.d_theta1 + D.d_psi)) +
           q_rate * relative * D.d_theta1_rate + q_rate * q_rate * slope * D.d_theta1_acc;
  if (follows) column -= q_rate * relative * D.d_gamma_rate;
  return column;
}

// The drives' parameters: Δω, ΔΩ, then every harmonic coefficient of the main and platform rate ripples.
std::vector<int> drive_parameters(const ErrorLayout& layout) {
  std::vector<int> parameters{int(ch::domega), int(ch::dOmega)};
  for (int channel : {int(ch::ripple1), int(ch::ripple3)})
    for (int k = 1; k <= layout.harmonic_order(); ++k)
      for (bool sine : {false, true}) parameters.push_back(layout.harmonic_index(channel, k, sine));
  return parameters;
}

// The drives' columns in closed form (β = 0). Δω changes θ̇1 by 1, θ1(t) by t and, on a counter-rotating
// platform, γ̇ by −1 and γ(t) by −t; ΔΩ changes γ̇ by −1 and γ(t) by −t there, nothing on a fixed one.
void closed_form_drive_columns(const Geometry& geo, const ErrorLayout& layout, const JointState<double>& j,
                               const NominalInstrument& nom, PlatformMode mode, double t,
                               const std::vector<int>& parameters, SensitivityMatrix& sensitivity) {
  const DriveDerivatives D = drive_derivatives(geo, j, nom);
  const bool counter = mode == PlatformMode::counter_rotating;
  Column d_domega = D.d_theta1_rate + t * (D.d_theta1 + D.d_psi);
  Column d_dOmega = Column::Zero();
  if (counter) {
    d_domega += -D.d_gamma_rate - t * D.d_psi;
    d_dOmega = -D.d_gamma_rate - t * D.d_psi;
  }
  const bool follows = counter && geo.platform_control == PlatformControl::phase_locked;
  sensitivity.col(layout.static_index(ch::domega)) = d_domega;
  sensitivity.col(layout.static_index(ch::dOmega)) = d_dOmega;
  for (std::size_t i = 2; i < parameters.size(); ++i)
    sensitivity.col(parameters[i]) = ripple_column(layout, parameters[i], j, D, counter, follows);
}

// No closed form is kept for a tilted horizontal axis: the drives' columns by central differences of the
// exact chain, step 1e-7 (rad/s for the rates, relative for the ripple; error O(h²·∂³) ≈ 1e-14 relative on
// outputs that are quadratic in the rates).
void drive_columns_by_differences(const Geometry& geo, const ErrorLayout& layout, const Site& site,
                                  const RunMotion<double>& run, PlatformMode mode, double t,
                                  const std::vector<int>& parameters, SensitivityMatrix& sensitivity) {
  const bool counter = mode == PlatformMode::counter_rotating;
  const double h = 1e-7;
  for (int index : parameters) {
    Eigen::VectorXd ep = Eigen::VectorXd::Zero(layout.size()), em = ep;
    ep[index] = h;
    em[index] = -h;
    auto eval = [&](const Eigen::VectorXd& err) {
      RunMotion<double> r = run;
      r.theta1_rate += err[ch::domega];
      if (counter) r.gamma_rate -= err[ch::domega] + err[ch::dOmega];
      const RunMotion<double> rippled = run_motion<double>(0.0, 0.0, 0.0, mode, geo, layout, err);
      r.main_ripple = rippled.main_ripple;
      r.platform_ripple = rippled.platform_ripple;
      r.platform_follows_main = rippled.platform_follows_main;
      const auto s = exact_state<double>(geo, layout, err, site, r.at(t));
      Column y;
      y << s.specific_force, s.angular_rate;
      return y;
    };
    sensitivity.col(index) = (eval(ep) - eval(em)) / (2 * h);
  }
}

// What the paper's first-order rules of one instant take: the g-level A, the radius R0, gravity (in the
// g-levels' g), the lever arms h = L + l and l (0 without them), the rate Ω and the platform angle's cos γ,
// sin γ.
struct PaperQuantities {
  double A, R0, gravity, h, l, Omega, cg, sg;
};

// The paper's Eq.(14) for one channel of unit value v: its first-order change of a_i and of ω_IA ({0, 0} for
// a channel the paper does not model).
std::pair<double, double> paper_rule(int channel, double v, const PaperQuantities& q) {
  double dai = 0.0, dwi = 0.0;
  switch (channel) {
    // θx group: a_i ∋ +(1 + A(L+l)/R0) θx sin γ;  ω_IA ∋ +Ω θx sin γ.
    case ch::dthx3t:
    case ch::dthx3:
      dai = (q.gravity + q.A * q.h / q.R0) * q.sg * v;
      dwi = q.Omega * q.sg * v;
      break;
    // θy group: a_i ∋ −(1 + A(L+l)/R0) θy cos γ;  ω_IA ∋ −Ω θy cos γ.
    case ch::dthy2t:
    case ch::dthy2:
    case ch::dthy3t:
    case ch::dthy3:
      dai = -(q.gravity + q.A * q.h / q.R0) * q.cg * v;
      dwi = -q.Omega * q.cg * v;
      break;
    case ch::dy2t:
    case ch::dy2:
    case ch::dy3t:
    case ch::dy3:
      dai = -q.A / q.R0 * q.sg * v;
      break;
    case ch::dthz5:
    case ch::dthz2:
      dai = q.A * q.sg * v;
      break;
    case ch::dR_s:
    case ch::dx2:
    case ch::dx3:
      dai = -q.A / q.R0 * q.cg * v;
      break;
    case ch::arm_stretch:
      dai = -q.A / q.R0 * q.cg * q.Omega * q.Omega;
      break;
    case ch::dx5:
      dai = -q.A / q.R0;
      break;
    case ch::dthy4:
      dai = -q.gravity - q.A * q.l / q.R0;
      break;
    case ch::dthy5:
      dai = -q.gravity;
      break;
    case ch::domega:
      dai = -2.0 * q.A / q.Omega * q.cg;
      break;  // amplitude only: A ∝ (Ω+Δω)² (Eq.19)
    default:
      break;  // not in the paper's Eq.(14)
  }
  return {dai, dwi};
}

}  // namespace

FirstOrderResult exact_first_order(const Geometry& geo, const ErrorLayout& layout, const Site& site,
                                   const RunMotion<double>& run, PlatformMode mode, double t) {
  const JointState<double> j = run.at(t);
  const NominalChain chain = nominal_chain(geo, j);
  const NominalInstrument nom = nominal_instrument(chain.instrument, site);

  FirstOrderResult out;
  out.nominal << nom.RT * nom.f / nom.unit, nom.RT * nom.w_inertial;
  out.sensitivity = SensitivityMatrix::Zero(6, layout.size());
  JointTrig trig(j);
  for (int index = 0; index < layout.size(); ++index) {
    const Channel& ch = channels()[layout.parameter_channel(index)];
    if (ch.link == Link::drive) continue;  // below
    ChannelValue<double> b = basis(layout, index, j, trig);
    if (ch.kind == ErrorKind::arm_stretch) b = {j.theta1_rate * j.theta1_rate, 0.0, 0.0};
    out.sensitivity.col(index) = link_error_column(chain.links[static_cast<int>(ch.link)], nom, ch.kind, b);
  }
  const std::vector<int> drives = drive_parameters(layout);
  if (geo.beta == 0.0)
    closed_form_drive_columns(geo, layout, j, nom, mode, t, drives, out.sensitivity);
  else
    drive_columns_by_differences(geo, layout, site, run, mode, t, drives, out.sensitivity);
  return out;
}

FirstOrderResult paper_first_order(const Geometry& geo, const ErrorLayout& layout, const Site& site,
                                   const JointState<double>& j, const PaperFormOptions& options) {
  // Forces in the g of the g-levels (Site::g_unit); gravity is g/g_unit of it (1 per the local g).
  const double R0 = geo.R0, A = R0 * j.theta1_rate * j.theta1_rate / site.g_unit();
  const double gravity = site.g / site.g_unit();
  const double cg = std::cos(j.gamma), sg = std::sin(j.gamma);
  const double h = options.lever_arms ? geo.L + geo.l : 0.0;
  const double l = options.lever_arms ? geo.l : 0.0;
  const double Omega = j.theta1_rate;
  const double coriolis = 2.0 * site.earth_rate * (site.earth_rotation && site.apply_coriolis ? 1.0 : 0.0) *
                          R0 * Omega * std::sin(site.latitude) / site.g_unit();

  FirstOrderResult out;
  out.sensitivity = SensitivityMatrix::Zero(6, layout.size());
  // Nominal: a_i = −A cos γ − Coriolis (constant or × cos γ); ω_IA = Earth rate on the IA azimuth.
  const double psi = j.theta1 + j.gamma;
  const Eigen::Vector3d earth = site.sensed_rate_enu();
  out.nominal.setZero();
  out.nominal[0] = -A * cg - coriolis * (options.constant_coriolis ? 1.0 : cg);
  out.nominal[3] = std::cos(psi) * earth.x() + std::sin(psi) * earth.y();

  const PaperQuantities q{A, R0, gravity, h, l, Omega, cg, sg};
  JointTrig trig(j);
  for (int index = 0; index < layout.size(); ++index) {
    const int channel = layout.parameter_channel(index);
    const ChannelValue<double> b = basis(layout, index, j, trig);
    const auto [dai, dwi] = paper_rule(channel, b.value, q);
    out.sensitivity(0, index) = dai;
    out.sensitivity(3, index) = dwi;
  }
  return out;
}

}  // namespace ccal
