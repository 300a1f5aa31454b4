#pragma once
// The elastic moduli of a hexagonal lattice of equal discs with linear contacts, in closed form:
// what a continuum must have to match the particles it is coupled to (the patch test).
//
// Derivation (the standard energy argument; Griffiths & Mustoe 2001, Int. J. Numer. Meth. Engng
// 50:1759-1775, and Kruyt & Rothenburg 2004 for the micromechanics). Discs of radius r touch six
// neighbours at branch vectors b = d n (d = 2r), n at 0, 60 and 120 degrees (and their opposites),
// each contact with a normal spring kn and a tangential spring ks [N/m/m]. The lattice is Bravais
// (one disc per cell) and every disc is a centre of symmetry, so a uniform strain eps moves the
// discs affinely and does not turn them (the tangential forces of opposite contacts cancel, and
// their moments sum to 2 r ks d sum_n n.eps.t, zero over three directions 60 degrees apart).
// Each contact then stores
//   1/2 kn (d n.eps.n)^2 + 1/2 ks (d n.eps.t)^2,   t = perp(n),
// and there are three contacts per disc, on a cell of area A = sqrt(3)/2 d^2. With the sums over
// the three directions
//   sum (n.eps.n)^2 = 3/8 ((tr eps)^2 + 2 eps:eps),   sum |eps n|^2 = 3/2 eps:eps,
//   sum (n.eps.t)^2 = sum |eps n|^2 - sum (n.eps.n)^2 = 3/4 eps:eps - 3/8 (tr eps)^2,
// the energy density is  W = d^2 / (2 A) [3/8 (kn - ks) (tr eps)^2 + 3/4 (kn + ks) eps:eps],
// i.e. W = 1/2 lambda (tr eps)^2 + mu eps:eps with d^2 / A = 2 / sqrt(3):
//   lambda_2D = sqrt(3)/4 (kn - ks),   mu = sqrt(3)/4 (kn + ks)
// (so the 2D Young modulus 2 sqrt(3) kn (kn + ks) / (3 kn + ks) and Poisson ratio
// (kn - ks) / (3 kn + ks) of the literature). Independent of the disc size.
//
// The continuum is plane strain: its in-plane law is lambda tr(eps) I + 2 mu eps with
// lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)). Matching both Lame constants gives
//   nu = lambda_2D / (2 (lambda_2D + mu)) = (kn - ks) / (4 kn),   E = 2 mu (1 + nu),
// so nu <= 1/4, and ks > kn gives a negative nu (allowed down to -1, ks < 5 kn).
namespace geohybrid::coupling
{
struct HexagonalLatticeModuli
{
  double lame_lambda = 0.0;   ///< lambda (in-plane) [Pa]
  double shear_modulus = 0.0; ///< mu [Pa]
  double young_modulus_plane_strain = 0.0; ///< E of the plane-strain continuum with the same in-plane law [Pa]
  double poisson_ratio_plane_strain = 0.0; ///< nu of that continuum [-]
  double density_factor = 0.0; ///< solid fraction pi / (2 sqrt(3)): continuum density = this x the discs' density [-]
};

/// Throws std::invalid_argument naming 'normal stiffness' or 'shear stiffness' if kn <= 0, ks < 0
/// or ks >= 5 kn (nu <= -1: no plane-strain continuum matches).
HexagonalLatticeModuli hexagonal_lattice_moduli(double contact_normal_stiffness, double contact_shear_stiffness);
} // namespace geohybrid::coupling
