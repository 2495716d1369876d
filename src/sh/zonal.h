#pragma once
// Zonal harmonics (functions symmetric about an axis), Funk-Hecke convolution, the clamped cosine
// and irradiance. A zonal function about +z has coefficients only at m = 0; we store those "zonal
// coefficients" z_l = integral of f(d) Y_l0(d) dd, one per band, so that
//   f(d) = sum_l z_l Y_l0(d) = sum_l z_l sqrt((2l+1)/(4 pi)) P_l(d.z).
// Funk-Hecke: convolving any function with a zonal kernel h multiplies its band-l coefficients by
// sqrt(4 pi / (2l+1)) h_l = 2 pi integral_{-1}^{1} h(t) P_l(t) dt (a plain number per band).
#include <glm/vec3.hpp>

#include "sh/coefficients.h"

namespace prt::sh {

/// Legendre polynomial P_l(x) for l >= 0 and x in [-1, 1], by the three-term recurrence
/// (P_l(1) = 1). The recurrence is stable: the error grows about like l ulp.
double legendre(int l, double x);

/// Derivative P_l'(x) for l >= 0 and x in [-1, 1], from P_(l+1)' = P_(l-1)' + (2l+1) P_l. Finite at
/// x = +-1 (P_l'(1) = l (l+1) / 2), unlike the closed form l (x P_l - P_(l-1)) / (x^2 - 1).
double legendre_derivative(int l, double x);

/// Funk-Hecke factor of the clamped cosine max(cos theta, 0) for band l >= 0: A_l, such that the
/// irradiance E_lm = A_l L_lm. A_0 = pi, A_1 = 2pi/3, A_2 = pi/4, A_3 = 0, A_4 = -pi/24, odd l > 1 give 0.
/// Closed form for any l (Ramamoorthi and Hanrahan 2001, eq. 8):
///   A_l = 2 pi (-1)^(l/2 - 1) / ((l + 2)(l - 1)) * l! / (2^l ((l/2)!)^2)   for even l >= 2,
/// with the central binomial term l! / (2^l ((l/2)!)^2) = prod_{k=1}^{l/2} (2k - 1) / (2k) evaluated as
/// that product (no factorials, no overflow, relative error ~ l ulp for any l).
double clamped_cosine_factor(int l);

/// Zonal coefficient of max(cos theta, 0) about +z: z_l = sqrt((2l+1)/(4 pi)) * A_l.
double clamped_cosine_zonal(int l);

/// Value of the zonal function with coefficients zonal[0..bands) at angle gamma from its axis:
/// sum_l zonal[l] sqrt((2l+1)/(4 pi)) P_l(cos_gamma). Precondition: bands >= 1, cos_gamma in [-1, 1].
double zonal_value(int bands, const double* zonal, double cos_gamma);

/// Expands a zonal function with coefficients zonal[0..bands) about `axis` (unit) into full SH:
/// out[index(l, m)] = sqrt(4 pi / (2l+1)) * zonal[l] * Y_lm(axis). `out` holds bands^2 values.
/// The result g satisfies g(d) = f(axis . d) where f is the zonal function about +z (addition theorem).
/// Preconditions: 1 <= bands <= kMaxBands, |axis| = 1.
void zonal_to_sh(int bands, const double* zonal, const glm::dvec3& axis, double* out);

/// Funk-Hecke convolution of f (coefficients, bands^2) with a zonal kernel h (zonal[0..bands)):
/// (h * f)_lm = sqrt(4 pi / (2l+1)) h_l f_lm, in place. The convolution is
/// (h * f)(a) = integral over S^2 of h(a . d) f(d) dd. The RGB form uses coefficients.bands bands.
void convolve_zonal(int bands, const double* kernel_zonal, double* coefficients);
void convolve_zonal(const double* kernel_zonal, RgbCoefficients& coefficients);

/// Irradiance at unit normal n from radiance coefficients: E(n) = sum_lm A_l L_lm Y_lm(n), in the
/// radiance's units times steradians. Lambert exit radiance is albedo * E / pi. A constant radiance L
/// gives E = pi L. Specialised (no basis evaluation) for bands <= 3. Precondition: 1 <= bands <= kMaxBands.
glm::dvec3 irradiance(const RgbCoefficients& radiance, const glm::dvec3& normal);

/// Scalar form: radiance[0..bands^2).
double irradiance(int bands, const double* radiance, const glm::dvec3& normal);

}  // namespace prt::sh
