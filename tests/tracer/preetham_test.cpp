// The Preetham sky against the paper's own formulas (Preetham, Shirley & Smits 1999, Appendix
// A.2): zenith luminance and chromaticity, and the Perez distribution relative to the zenith,
// transcribed here afresh in the paper's matrix form.
#include <cmath>

#include <gtest/gtest.h>

#include "common/math.h"
#include "tracer/lights/sky.h"

namespace arbor::tracer {

namespace {

struct Zenith {
  double x, y, Y;  // chromaticity, luminance in kcd/m²
};

// Appendix A.2: Y_z = (4.0453 T − 4.9710) tan χ − 0.2155 T + 2.4192, χ = (4/9 − T/120)(π − 2θs);
// x_z, y_z = [T² T 1] M [θs³ θs² θs 1]ᵀ.
Zenith paper_zenith(double T, double theta_s) {
  const double mx[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                           {-0.02903, 0.06377, -0.03202, 0.00394},
                           {0.11693, -0.21196, 0.06052, 0.25886}};
  const double my[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                           {-0.04214, 0.08970, -0.04153, 0.00516},
                           {0.15346, -0.26756, 0.06670, 0.26688}};
  const double tv[3] = {T * T, T, 1.0};
  const double sv[4] = {theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1.0};
  Zenith z{0.0, 0.0, 0.0};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      z.x += tv[i] * mx[i][j] * sv[j];
      z.y += tv[i] * my[i][j] * sv[j];
    }
  }
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2.0 * theta_s);
  z.Y = (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;
  return z;
}

// Appendix A.2's luminance coefficients of the Perez function F(θ, γ).
double perez_luminance(double T, double theta, double gamma) {
  const double A = 0.1787 * T - 1.4630, B = -0.3554 * T + 0.4275, C = -0.0227 * T + 5.3251,
               D = 0.1206 * T - 2.5771, E = -0.0670 * T + 0.3703;
  return (1.0 + A * std::exp(B / std::cos(theta))) *
         (1.0 + C * std::exp(D * gamma) + E * std::cos(gamma) * std::cos(gamma));
}

// arbor's sky scales the model so that a sun of irradiance E stands for 100 klux.
constexpr double kSunE = 3.0, kScale = kSunE * 1000.0 / 100000.0;

}  // namespace

TEST(Preetham, ZenithLuminanceAndChromaticityAreThePapers) {
  for (double T : {2.0, 3.0, 6.0, 10.0}) {
    for (double sun_zenith_deg : {0.0, 30.0, 45.0, 60.0, 80.0}) {
      const double ts = sun_zenith_deg * kPi / 180.0;
      const glm::dvec3 xyz = preetham_xyz(T, 0.0, ts, ts, kSunE);
      const double sum = xyz.x + xyz.y + xyz.z;
      const Zenith z = paper_zenith(T, ts);
      EXPECT_NEAR(xyz.x / sum, z.x, 1e-9) << "T " << T << " sun zenith " << sun_zenith_deg;
      EXPECT_NEAR(xyz.y / sum, z.y, 1e-9) << "T " << T << " sun zenith " << sun_zenith_deg;
      EXPECT_NEAR(xyz.y / kScale, z.Y, 1e-9 * z.Y) << "T " << T << " sun zenith " << sun_zenith_deg;
    }
  }
  // What the formulas say of a clear sky (T = 3, sun 45° up): a zenith bluer than D65
  // (x 0.3127, y 0.3290) at about 7.3 kcd/m², brighter the higher the sun.
  const Zenith clear = paper_zenith(3.0, kPi / 4.0);
  EXPECT_NEAR(clear.x, 0.2457, 5e-5);
  EXPECT_NEAR(clear.y, 0.2515, 5e-5);
  EXPECT_NEAR(clear.Y, 7.3204, 5e-4);
  EXPECT_GT(paper_zenith(3.0, 0.3).Y, paper_zenith(3.0, 0.9).Y);
}

TEST(Preetham, LuminanceFollowsThePerezDistributionFromTheZenith) {
  // Y(θ, γ) = Y_z F(θ, γ) / F(0, θs) for view directions all over the sky.
  const double T = 3.0, ts = 50.0 * kPi / 180.0;
  const double Yz = paper_zenith(T, ts).Y * kScale;
  for (double theta : {0.1, 0.6, 1.0, 1.4, 1.55}) {
    for (double gamma : {0.05, 0.5, 1.2, 2.0, 3.0}) {
      const double expected = Yz * perez_luminance(T, theta, gamma) / perez_luminance(T, 0.0, ts);
      EXPECT_NEAR(preetham_xyz(T, theta, gamma, ts, kSunE).y, expected, 1e-9 * expected)
          << "theta " << theta << " gamma " << gamma;
    }
  }
  // The circumsolar region is brighter than the sky 90° from the sun at the same height.
  EXPECT_GT(preetham_xyz(T, ts, 0.05, ts, kSunE).y, preetham_xyz(T, ts, kPi / 2.0, ts, kSunE).y);
}

}  // namespace arbor::tracer
