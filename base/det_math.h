// Deterministic trigonometry: the same bits on every machine, compiler and build type.
//
// Implements: sine, cosine and tangent of a double by range reduction with a fixed 2π and a Taylor
// series evaluated in a fixed order. Built with -ffp-contract=off (CMakeLists.txt), so no step is
// fused. Everything that decides geometry (scene matrices, camera paths, field-of-view tangents,
// glTF texture-transform rotations) uses these, because libm's sin/cos/tan are not promised to give
// the same bits across libm versions or machines.
// Does not implement: inverse functions, float overloads, or correctly rounded results. The series
// stops after the x^23 term, so the absolute error grows towards ±π, where it reaches 1.71e-13
// (measured against glibc's sin on 4,000,001 points of [-π, π]); on [-π/2, π/2] it is at most 4.4e-16.
// What matters here is that it is the same error on every machine.
// GLM provides the vector and matrix arithmetic (plain IEEE operations); its trigonometry calls libm,
// so projections and rotations are built from these functions instead (never glm::perspective /
// glm::rotate).
#pragma once

namespace tessera {

constexpr double kPi = 3.14159265358979323846;

double detSin(double x);
double detCos(double x);
// detSin(x) / detCos(x): one division, so callers that used that quotient keep their bits.
double detTan(double x);

}  // namespace tessera
