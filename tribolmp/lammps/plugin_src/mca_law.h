/* -*- c++ -*- ---------------------------------------------------------
   tribolmp MCA plugin: the movable-cellular-automata interaction law.

   One small function per rule.  Everything here is in LAMMPS units of the
   calling deck (the tribolmp decks use "units nano": nm, ns, ag; pressure
   unit 1 MPa, force unit 1 pN).  The derivation of every rule is in
   docs/mca.md ("The MCA law"); the short form is repeated next to each
   function so that the C++ can be read on its own.

   Geometry of a pair (automata a, b; radii r_a, r_b; dbar = r_a + r_b):
     n      unit vector from a to b,
     A      the pair's contact area, chosen so that the Love-Weber stress of a
            perfect lattice (hexagonal 2D, FCC 3D) equals the pair traction:
            A dbar / (2 V) = D / Z  =>  A = dbar^2/(2 sqrt 2) (3D, V = d^3/sqrt 2)
                                        A = dbar^2/sqrt 3     (2D sheet of thickness d,
                                                              V = sqrt(3)/2 d^3)
   Pair traction on a:  t = sigma_n n + tau  (tau perpendicular to n),
   force on a:  F_a = A t,  force on b:  F_b = -F_a.
------------------------------------------------------------------------- */

#ifndef TRIBOLMP_MCA_LAW_H
#define TRIBOLMP_MCA_LAW_H

#include <cmath>

namespace MCALaw {

static constexpr double SQRT2 = 1.41421356237309504880;
static constexpr double SQRT3 = 1.73205080756887729353;

// Material of the automata (LAMMPS units).  Derived quantities are set by
// derive(); alpha is the weight of the many-body mean-stress term.
struct Material {
  int dim = 3;
  double G = 0.0;        // shear modulus
  double nu = 0.0;       // Poisson ratio
  double sy = 0.0;       // initial yield stress sigma_y
  double s0 = 0.0;       // ultimate strength sigma_0 (end of hardening, link strength)
  double H = 0.0;        // linear isotropic hardening modulus d sigma_y / d eps_p
  double mu = 0.0;       // Coulomb friction of unlinked contacts
  double eta = 0.0;      // viscosity of unlinked contacts (pressure * time)
  double wfac = 0.0;     // weld strength / sigma_0
  double wonset = 0.0;   // compressive pair stress that welds an unlinked contact
  double damp = 0.0;     // link damping, fraction of critical
  // derived
  double alpha = 0.0;    // mean-stress weight
  double lambda = 0.0;   // Lame's first parameter
  double Kc = 0.0;       // normal stiffness of an unlinked contact (stress per strain)
  double inv_3GH = 0.0;  // 1 / (3G + H) and 1 / (3G) (the radial return's denominators)
  double inv_3G = 0.0;

  // Rule 0 (elastic constants).  With pair traction t = 2G eps.n + alpha X n, the
  // Love-Weber stress of a Bravais lattice is sigma = 2G eps + alpha X I (because
  // sum_j n n = (Z/D) I); X = mean stress at equilibrium gives Hooke's law when
  //   3D:  alpha = lambda/K       = 3 nu / (1 + nu)      (X = sigma_kk / 3)
  //   2D plane strain: alpha = lambda/(lambda + G) = 2 nu  (X = in-plane mean)
  // An unlinked contact carries only the volumetric pair stiffness
  //   Kc = 2G / (1 - alpha)  (= 3K in 3D, = 2(lambda+G) in 2D),
  // which is what a link carries under an isotropic compression.
  void derive() {
    lambda = 2.0 * G * nu / (1.0 - 2.0 * nu);
    alpha = (dim == 3) ? 3.0 * nu / (1.0 + nu) : 2.0 * nu;
    Kc = 2.0 * G / (1.0 - alpha);
    inv_3GH = 1.0 / (3.0 * G + H);
    inv_3G = 1.0 / (3.0 * G);
  }
};

// Pair contact area A (see the header comment).
inline double pair_area(double dbar, int dim)
{
  return (dim == 3) ? dbar * dbar / (2.0 * SQRT2) : dbar * dbar / SQRT3;
}

// Volume of one automaton of diameter d (Voronoi cell of the close-packed lattice;
// in 2D a sheet of thickness d).
inline double automaton_volume(double d, int dim)
{
  return (dim == 3) ? d * d * d / SQRT2 : 0.5 * SQRT3 * d * d * d;
}

// Rule 1 (linked pair response).  The strain of the pair is split between a and b
// so that their responses are equal:  2G e_a + alpha X_a = 2G e_b + alpha X_b with
// (e_a + e_b)/2 = e gives the common response
//   sigma_n = 2G e + alpha (X_a + X_b)/2,   tau = 2G xi / dbar,
// e = (r - dbar)/dbar - p_n (p_n: the pair's plastic normal offset),
// xi = elastic tangential displacement of b relative to a (plastic part removed).
inline double link_normal(const Material &m, double e, double Xbar)
{
  return 2.0 * m.G * e + m.alpha * Xbar;
}
inline double shear_factor(const Material &m, double dbar)
{
  return 2.0 * m.G / dbar;    // tau = shear_factor * xi
}

// Rule 2 (unlinked contact).  Repulsion only while the automata overlap
// (e_raw = (r - dbar)/dbar < 0): sigma_n = Kc e_raw <= 0; no tension.
// Friction: the tangential response is capped at mu |sigma_n| (Coulomb);
// returns the factor (<= 1) by which xi must be scaled.
inline double contact_normal(const Material &m, double eraw)
{
  return (eraw < 0.0) ? m.Kc * eraw : 0.0;
}
inline double coulomb_scale(const Material &m, double sig_n, double tau_mag)
{
  const double cap = m.mu * std::fabs(sig_n);
  return (tau_mag > cap && tau_mag > 0.0) ? cap / tau_mag : 1.0;
}

// Rule 3 (fracture of a link).  A link breaks when the pair equivalent stress
//   s_pe = sqrt( max(sigma_n, 0)^2 + 3 |tau|^2 )
// exceeds its strength (sigma_0 for a bulk link, wfac sigma_0 for a weld).  In a
// uniform stress state the pair traction is sigma.n, so for a uniaxial stress S a
// link at angle theta to the axis carries sigma_n = S cos^2, tau = S cos sin and
// s_pe = S cos(theta) sqrt(1 + 2 sin^2(theta)) = S along the axis and at 45 deg
// (the hexagonal and the FCC[100] link families): rupture at the ultimate
// strength.  Compression alone never breaks a link (sigma_n <= 0 drops out and
// sqrt(3)|tau| <= von Mises stress <= sigma_0 as long as plasticity caps it, with
// equality only for pure shear on top of the pressure).
inline bool link_breaks_sq(double sig_n, double tau_sq, double strength)
{
  const double t = (sig_n > 0.0) ? sig_n : 0.0;
  return t * t + 3.0 * tau_sq > strength * strength;    // tau_sq = |tau|^2 (no square root)
}
inline bool link_breaks(double sig_n, double tau_mag, double strength)
{
  return link_breaks_sq(sig_n, tau_mag * tau_mag, strength);
}

// Rule 4 (welding).  An unlinked contact pressed with a compressive pair stress
// of at least wonset becomes a weld link (strength wfac sigma_0), provided the
// weld would hold its current shear (rule 3 with the weld strength): a
// junction cannot form while the surfaces slide past each other faster than it
// can hold them (without this a sheared contact welds and breaks every step).
// The weld keeps the contact's force: its plastic offset p_n is chosen so that
//   2G (e_raw - p_n) + alpha Xbar = Kc e_raw.
inline bool welds(const Material &m, double sig_n, double tau_sq)
{
  return m.wfac > 0.0 && -sig_n >= m.wonset && !link_breaks_sq(sig_n, tau_sq, m.wfac * m.s0);
}
inline double weld_offset(const Material &m, double eraw, double Xbar)
{
  return eraw - (m.Kc * eraw - m.alpha * Xbar) / (2.0 * m.G);
}

// Rule 5 (rotation).  Linked automata resist relative rotation theta_rel = int
// (omega_b - omega_a) dt with a moment M_a = k_r theta_rel (M_b = -M_a): the
// bending stiffness of a square beam of area A and length dbar made of the
// pair's modulus 2G, k_r = 2G (A^2/12) / dbar.  Uniform strain rotates all
// automata alike, so k_r does not enter E or nu.
inline double rotational_stiffness(const Material &m, double A, double dbar)
{
  return 2.0 * m.G * A * A / (12.0 * dbar);
}

// Link damping (numerical, a fraction `damp` of critical): the constants of a linked pair of
// masses ma, mb and radii ra, rb, for the relative velocity (cd: the pair's volumetric normal
// stiffness Kc A / dbar against the reduced mass) and the relative rotation (cr: the rotational
// stiffness against the reduced moment of inertia of two spheres, I = 0.4 m r^2).  Fixed by
// the two automata, so they are recomputed rather than stored with the pair.
inline void link_damping(const Material &m, double ma, double mb, double ra, double rb, double A,
                         double dbar, double &cd, double &cr)
{
  const double meff = ma * mb / (ma + mb);
  const double kl = m.Kc * A / dbar;
  const double kr0 = rotational_stiffness(m, A, dbar);
  const double Ia = 0.4 * ma * ra * ra, Ib = 0.4 * mb * rb * rb;
  cd = m.damp * 2.0 * std::sqrt(kl * meff);
  cr = m.damp * 2.0 * std::sqrt(kr0 * Ia * Ib / (Ia + Ib));
}

// Rule 6 (viscosity of unlinked contacts, the seed's dissipative force):
// F_visc on a = eta A / dbar * v_rel (v_rel = velocity of b's contact point
// relative to a's).
inline double viscous_factor(const Material &m, double A, double dbar)
{
  return m.eta * A / dbar;
}

// Current yield stress: linear isotropic hardening from sigma_y, saturating at
// the ultimate strength sigma_0.
inline double yield_stress(const Material &m, double ep)
{
  const double s = m.sy + m.H * ep;
  return (s < m.s0) ? s : m.s0;
}

// Von Mises equivalent stress of a symmetric tensor (xx yy zz xy xz yz).
inline double von_mises(const double s[6])
{
  const double p = (s[0] + s[1] + s[2]) / 3.0;
  const double a = s[0] - p, b = s[1] - p, c = s[2] - p;
  return std::sqrt(1.5 * (a * a + b * b + c * c + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
}

// Rule 7 (plasticity per automaton, Wilkins radial return).  Trial stress
// sigma (xx yy zz xy xz yz); if sigma_eq > sigma_y(eps_p) the plastic multiplier
//   dgamma = (sigma_eq - sigma_y(eps_p)) / (3G + H)   (3G once sigma_0 is reached)
// takes the stress back to the yield surface along the deviator,
//   s <- s (1 - 3G dgamma / sigma_eq),  deps_p = 3/2 dgamma s / sigma_eq,
// and eps_p += dgamma.  Returns dgamma; deps (tensor, shear entries are tensor
// components) and the returned stress are written back.  The mean stress is
// untouched: yield does not depend on pressure.
// seq receives the von Mises stress of the stress written back (the deviator is scaled by
// f = 1 - 3G dgamma / sigma_eq >= 0, so it is f sigma_eq: sigma_y(eps_p + dgamma), or sigma_0).
inline double radial_return(const Material &m, double sig[6], double ep, double deps[6],
                            double &seq)
{
  const double s_eq = von_mises(sig);
  const double sy = yield_stress(m, ep);
  if (s_eq <= sy || s_eq <= 0.0) {
    for (int k = 0; k < 6; k++) deps[k] = 0.0;
    seq = s_eq;
    return 0.0;
  }
  // (one division: the constant denominators are the material's reciprocals)
  double dg = (s_eq - sy) * m.inv_3GH;
  if (yield_stress(m, ep + dg) >= m.s0) dg = (s_eq - m.s0) * m.inv_3G;
  if (dg < 0.0) dg = 0.0;
  const double is = 1.0 / s_eq;
  const double p = (sig[0] + sig[1] + sig[2]) / 3.0;
  const double f = 1.0 - 3.0 * m.G * dg * is;
  const double c = 1.5 * dg * is;
  double s[6] = {sig[0] - p, sig[1] - p, sig[2] - p, sig[3], sig[4], sig[5]};
  for (int k = 0; k < 6; k++) {
    deps[k] = c * s[k];
    sig[k] = f * s[k] + ((k < 3) ? p : 0.0);
  }
  seq = f * s_eq;
  return dg;
}

}    // namespace MCALaw

#endif
