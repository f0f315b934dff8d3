// A luminaire's candela distribution in the IES type C convention (LM-63): intensity by vertical
// angle theta, from the luminaire's nadir axis (0, straight down the axis, to 180, straight up),
// and horizontal angle phi, around that axis from its reference plane (0). Measured at a few angles
// and interpolated bilinearly between them; zero outside the vertical angles measured.
#pragma once

#include <string>
#include <vector>

namespace radfarm {

// The horizontal angles say which symmetry the table assumes, as LM-63 does:
//   {0}                     rotationally symmetric: one vertical plane serves all phi
//   0 .. 90                 symmetric in each quadrant
//   0 .. 180                bilaterally symmetric about the 0-180 plane
//   90 .. 270               bilaterally symmetric about the 90-270 plane
//   0 .. 360                no symmetry (360 repeats 0)
struct CandelaTable {
  std::vector<double> vertical;    // degrees, strictly increasing, within [0, 180]
  std::vector<double> horizontal;  // degrees, strictly increasing, one of the ranges above
  // candela[h * vertical.size() + v]: the intensity at horizontal[h], vertical[v], >= 0
  std::vector<double> candela;
};

// What is wrong with a table, or "" if nothing: angles out of range, not increasing or not one
// of the symmetries above; a candela count other than the product; a value negative or not
// finite.
std::string CandelaTableProblem(const CandelaTable& table);

// The intensity in candela toward (theta, phi) in degrees, theta in [0, 180], phi any angle
// (taken modulo 360). The table must have no problem.
double CandelaAt(const CandelaTable& table, double theta_deg, double phi_deg);

// The luminous flux in lumens the interpolated distribution emits: the integral of the
// intensity over the sphere, by the midpoint rule on a grid fine enough for 1e-4 relative error
// on smooth tables.
double TableLumens(const CandelaTable& table);

}  // namespace radfarm
